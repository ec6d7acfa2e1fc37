source "$(dirname "$0")/lib.sh"
# No result is lost: a second run of a run name that holds an earlier run is
# refused before mpirun starts (exit 1), with a message that names the run
# directory and the ways out (--overwrite, a new run.name, --resume), and it
# changes no file of the earlier run. The coupler daemon refuses by itself as
# well, when started without the launcher's check, and the post-mortem leaves
# that directory alone. With --overwrite the run replaces the directory.
cat > tiny.yaml <<YAML
run: {name: tiny, seed: 5}
materials:
  cu_cg:
    kind: dpd_mesoparticle
    mass: 508.37
    lattice_constant: 7.23
    potential_file: $ROOT/configs/potentials/cu_cg_morse.yaml
stages:
  - {name: static, kind: dpd_elastic, material: cu_cg, temperature: 0}
YAML
"$PBMS" run tiny.yaml > first.txt 2>&1 || { cat first.txt; fail "first run"; }
run="$PWD/runs/tiny"
[ -f "$run/summary.yaml" ] || fail "the first run wrote no summary.yaml"
echo "a note the user keeps beside the results" > "$run/notes.txt"
# Every entry with its size, mode and time, and every file's checksum.
state() {
  (cd "$run" && find . -printf '%p %y %s %m %T@\n' | sort &&
    find . -type f -print0 | sort -z | xargs -0 sha256sum)
}
before="$(state)"

# A fake mpirun first on PATH proves that no job starts.
mkdir -p fake
cat > fake/mpirun <<EOF
#!/bin/sh
touch "$PWD/mpirun-was-started"
exit 99
EOF
chmod +x fake/mpirun
set +e  # every check below reports; none ends the script
passed=0
check() {  # check CONDITION-STATUS TEXT
  if [ "$1" -eq 0 ]; then echo "ok   $2"; passed=$((passed + 1)); else echo "FAIL $2"; failed=1; fi
}
failed=0

rc=0
PATH="$PWD/fake:$PATH" "$PBMS" run tiny.yaml > second.txt 2>&1 || rc=$?
cat second.txt
[ "$rc" -eq 1 ]; check $? "a rerun of 'tiny' exits 1 (got $rc)"
[ ! -e mpirun-was-started ]; check $? "mpirun was not started"
grep -q "^tiny.yaml:1:[0-9]*: error: run.name: the run directory '$run' holds an earlier run" second.txt
check $? "the message is tiny.yaml:LINE:COL: error: run.name: ... and names $run"
grep -q -- "--overwrite" second.txt && grep -q "new run.name" second.txt && grep -q -- "--resume" second.txt
check $? "it names the options: --overwrite, a new run.name, --resume"
[ "$before" = "$(state)" ]; check $? "no file of the first run changed"

# --resume and --overwrite contradict each other.
rc=0
PATH="$PWD/fake:$PATH" "$PBMS" run tiny.yaml --resume --overwrite > both.txt 2>&1 || rc=$?
[ "$rc" -eq 1 ] && grep -q "give one of them" both.txt && [ ! -e mpirun-was-started ]
check $? "--resume with --overwrite is refused before mpirun"

# The daemon's own guard: started under mpirun without the launcher's plan.
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none PMIX_MCA_gds=hash
rc=0
mpirun --bind-to none -np 1 "$ROOT/build/bin/coupler" daemon tiny.yaml --run-id guard-test : \
  -np 1 "$ROOT/build/bin/dpd_driver" < /dev/null > daemon.txt 2>&1 || rc=$?
cat daemon.txt
[ "$rc" -ne 0 ] && grep -q "refused: tiny.yaml:1:[0-9]*: error: run.name: the run directory '$run' holds an earlier run" daemon.txt
check $? "the daemon refuses by itself (exit $rc)"
"$ROOT/build/bin/coupler" postmortem "$run" --exit-code "$rc" --mpirun-log daemon.txt \
  --run-id guard-test > postmortem.txt 2>&1
[ "$before" = "$(state)" ]; check $? "the daemon and the post-mortem of the refused job changed no file"

# Asked explicitly, the run replaces the directory.
"$PBMS" run tiny.yaml --overwrite > third.txt 2>&1 || { cat third.txt; fail "run with --overwrite"; }
[ ! -e "$run/notes.txt" ] && [ -f "$run/summary.yaml" ] &&
  grep -q "command: .*--overwrite" "$run/manifest.yaml" && grep -q "status: ok" "$run/manifest.yaml"
check $? "--overwrite replaced the run directory and ran"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
