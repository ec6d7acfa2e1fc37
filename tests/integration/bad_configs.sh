#!/usr/bin/env bash
# bad_configs.sh REPO_ROOT
#
# Every workflow under tests/configs/bad/ carries exactly one mistake. For each one,
# `./pbms run FILE` must refuse it before starting MPI:
#   - exit code exactly 1;
#   - stderr contains the expected substring: the first line of the file,
#     "# expect: <substring>", or for a file that cannot carry a comment (empty,
#     binary) the contents of the sibling NAME.expect (NAME without .yaml);
#   - every stderr line containing ': error: ' has the form
#     FILE:LINE:COL: error: KEY.PATH: message, and there is at least one;
#   - mpirun was never started (a fake mpirun first on PATH leaves a marker).
# Cases too big to commit (a config over 1 MiB, a line of megabytes, a
# potential file over 1 MiB, deep nesting) are generated into a temporary
# directory with a NAME.expect each and checked the same way; the line of
# megabytes also through `./pbms validate`, which used to die of a
# segmentation fault on it.
# Prints "ok NAME" or "FAIL NAME: reason" per case, then "N passed, M failed".
set -u

if [ $# -ne 1 ] || [ ! -d "$1" ]; then
  echo "usage: $0 REPO_ROOT" >&2
  exit 2
fi
ROOT="$(cd "$1" && pwd)"
BAD_DIR="tests/configs/bad"
ERROR_LINE_RE='^[^:]+:[0-9]+:[0-9]+: error: [^ ]+: '

[ -x "$ROOT/pbms" ] || { echo "FAIL setup: $ROOT/pbms is not executable"; echo "0 passed, 1 failed"; exit 1; }
[ -d "$ROOT/$BAD_DIR" ] || { echo "FAIL setup: $ROOT/$BAD_DIR does not exist"; echo "0 passed, 1 failed"; exit 1; }

# ctest built the tree; a no-op build costs seconds per case, and refusing a
# config does not depend on it.
export PBMS_SKIP_BUILD=1
TMP="$(mktemp -d -t pbms-bad-configs.XXXXXX)"
trap 'rm -rf "$TMP"' EXIT
mkdir "$TMP/bin"
cat >"$TMP/bin/mpirun" <<'EOF'
#!/bin/sh
# Fake mpirun: records that it was started (in the case's own marker) and
# fails loudly.
touch "$PBMS_TEST_MPIRUN_MARKER"
exit 99
EOF
chmod +x "$TMP/bin/mpirun"

# The expected substring of one case, or nothing (status 1) if it has none.
expected_substring() {
  local file="$1" sibling="${1%.yaml}.expect" line=""
  if [ -f "$sibling" ]; then
    IFS= read -r line <"$sibling"
  else
    IFS= read -r line <"$file"
    case "${line:-}" in
      "# expect: "*) line="${line#\# expect: }" ;;
      *) line="" ;;
    esac
  fi
  line="${line%$'\r'}"
  [ -n "${line:-}" ] || return 1
  printf '%s\n' "$line"
}

# Checks one case (a path relative to ROOT, or absolute); prints nothing and
# returns 0 if it passes, else prints the reason. COMMAND is run or validate.
# Each case has its own files, so that two run at once.
check_case() {
  local rel="$1" command="${2:-run}" file expect rc own
  own="$(mktemp -d "$TMP/case.XXXXXX")"
  local out="$own/stdout" err="$own/stderr" MARKER="$own/mpirun-was-started"
  case "$rel" in /*) file="$rel" ;; *) file="$ROOT/$rel" ;; esac
  expect="$(expected_substring "$file")" ||
    { echo "no '# expect: ' first line and no .expect sibling"; return 1; }
  (cd "$ROOT" && PBMS_TEST_MPIRUN_MARKER="$MARKER" PATH="$TMP/bin:$PATH" ./pbms "$command" "$rel") \
    </dev/null >"$out" 2>"$err"
  rc=$?
  local reasons=()
  [ "$rc" -eq 1 ] || reasons+=("exit code $rc, expected 1")
  grep -qaF -- "$expect" "$err" || reasons+=("stderr lacks '$expect'")
  local error_lines bad_lines
  error_lines="$(grep -aF ': error: ' "$err")"
  if [ -z "$error_lines" ]; then
    reasons+=("no 'FILE:LINE:COL: error: KEY: message' line on stderr")
  else
    bad_lines="$(grep -avE -- "$ERROR_LINE_RE" <<<"$error_lines")"
    [ -z "$bad_lines" ] || reasons+=("malformed error line: $(head -n 1 <<<"$bad_lines")")
  fi
  [ ! -e "$MARKER" ] || reasons+=("mpirun was started")
  if [ "${#reasons[@]}" -gt 0 ]; then
    local msg
    msg="$(printf '%s; ' "${reasons[@]}")"
    echo "${msg%; }"
    return 1
  fi
  return 0
}

# The generated cases, each with its NAME.expect.
GEN="$TMP/generated"
mkdir "$GEN"
# A run of one character, COUNT long, without a newline: repeat CHAR COUNT.
repeat() { head -c "$2" /dev/zero | tr '\0' "$1"; }
good_head='run: {name: big}
materials:
  cu: {kind: eam_alloy, potential: /usr/share/lammps/potentials/Cu_mishin1.eam.alloy, mass: 63.546, lattice_constant: 3.615}
stages:
  - {name: el, kind: md_elastic, material: cu}'
# 1. Over 1 MiB in ordinary lines: a good workflow and 20,000 comment lines.
comment="# $(repeat x 60)"
{
  echo "$good_head"
  for _ in $(seq 20000); do echo "$comment"; done
} >"$GEN/over_1mib.yaml"
echo "over_1mib.yaml:1:1: error: <document>: the file is" >"$GEN/over_1mib.expect"
# 2. One line of 5 MB (a quoted run name): `./pbms validate` died of SIGSEGV.
{ printf 'run: {name: "'; repeat a 5000000; printf '"}'; } >"$GEN/one_line_5mb.yaml"
echo "one_line_5mb.yaml:1:1: error: <document>: the file is 5000015 bytes; a workflow is at most" \
  >"$GEN/one_line_5mb.expect"
# 3. A line of 200 kB in a file under 1 MiB.
{
  echo "run: {name: long_line}"
  printf 'launch: {md: 1}  # %s\n' "$(repeat y 200000)"
  echo "$good_head" | tail -n +2
} >"$GEN/long_line.yaml"
echo "long_line.yaml:2:1: error: <document>: line 2 is 200019 bytes long" >"$GEN/long_line.expect"
# 4. A potential file over 1 MiB: reported with its own name.
{
  echo "style: morse"
  for _ in $(seq 20000); do echo "$comment"; done
} >"$GEN/huge_potential.data"
{
  echo "run: {name: big_potential}"
  echo "materials:"
  echo "  cu_cg: {kind: dpd_mesoparticle, mass: 508.37, lattice_constant: 7.23, potential_file: huge_potential.data}"
  echo "stages:"
  echo "  - {name: el, kind: dpd_elastic, material: cu_cg, temperature: 0}"
} >"$GEN/potential_over_1mib.yaml"
echo "huge_potential.data:1:1: error: <document>: the file is" >"$GEN/potential_over_1mib.expect"
# 5. Lists nested 100,000 deep, in lines of 1,000 brackets.
{
  printf 'run: {name: deep}\nstages:\n'
  for _ in $(seq 100); do repeat '[' 1000; echo; done
  for _ in $(seq 100); do repeat ']' 1000; echo; done
} >"$GEN/deep_nesting.yaml"
echo "error: <document>: lists and maps are nested too deep" >"$GEN/deep_nesting.expect"

# One case: "ok NAME" or "FAIL NAME: reason" (NAME REL [COMMAND]).
report_case() {
  local reason
  if reason="$(check_case "$2" "${3:-run}")"; then
    echo "ok $1"
  else
    echo "FAIL $1: $reason"
  fi
}
export -f report_case check_case expected_substring
export ROOT TMP ERROR_LINE_RE
# The cases, two at a time (each is mostly the launcher's and the drivers'
# start-up), their lines in the cases' order.
shopt -s nullglob
{
  for path in "$ROOT/$BAD_DIR"/* "$GEN"/*.yaml; do
    [ -f "$path" ] || continue
    case "$path" in *.expect) continue ;; esac
    name="$(basename "$path")"
    case "$path" in "$GEN"/*) rel="$path" ;; *) rel="$BAD_DIR/$name" ;; esac
    printf '%s\0%s\0run\0' "$name" "$rel"
  done
  printf '%s\0%s\0validate\0' "one_line_5mb.yaml (./pbms validate)" "$GEN/one_line_5mb.yaml"
} | xargs -0 -n 3 -P 2 bash -c 'report_case "$@"' _ >"$TMP/report"
cat "$TMP/report"
passed=$(grep -c '^ok ' "$TMP/report")
failed=$(grep -c '^FAIL ' "$TMP/report")

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
