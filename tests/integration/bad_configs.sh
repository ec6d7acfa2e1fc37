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

TMP="$(mktemp -d -t pbms-bad-configs.XXXXXX)"
trap 'rm -rf "$TMP"' EXIT
mkdir "$TMP/bin"
MARKER="$TMP/mpirun-was-started"
cat >"$TMP/bin/mpirun" <<EOF
#!/bin/sh
# Fake mpirun: records that it was started and fails loudly.
touch "$MARKER"
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

# Checks one case; prints nothing and returns 0 if it passes, else prints the reason.
check_case() {
  local rel="$1" expect rc out="$TMP/stdout" err="$TMP/stderr"
  expect="$(expected_substring "$ROOT/$rel")" ||
    { echo "no '# expect: ' first line and no .expect sibling"; return 1; }
  rm -f "$MARKER"
  (cd "$ROOT" && PATH="$TMP/bin:$PATH" ./pbms run "$rel") </dev/null >"$out" 2>"$err"
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

passed=0
failed=0
shopt -s nullglob
for path in "$ROOT/$BAD_DIR"/*; do
  [ -f "$path" ] || continue
  case "$path" in *.expect) continue ;; esac
  name="$(basename "$path")"
  if reason="$(check_case "$BAD_DIR/$name")"; then
    echo "ok $name"
    passed=$((passed + 1))
  else
    echo "FAIL $name: $reason"
    failed=$((failed + 1))
  fi
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
