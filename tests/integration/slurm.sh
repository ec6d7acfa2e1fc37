source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/slurm_lib.sh"
# A cluster launch (docs/cluster.md): `./pbms run --slurm` writes a batch
# script; a one-node Slurm started here (slurm_lib.sh) runs it through
# sbatch, with srun --multi-prog and PBMS_APP in place of MPI_APPNUM; its
# summary.yaml equals that of the same config run by `./pbms run` (mpirun),
# every number to 1e-9 relative, and so do its HDF5 files. The workflow
# runs md, dpd and mpm stages (coupler + 1 + 1 + 2 ranks: four programs,
# five tasks). Also: a config that does not validate is refused by --slurm
# as by run (file:line:col, exit 1, nothing written); the script submitted
# a second time is refused by the job and changes nothing; and a multi-prog
# file without PBMS_APP ends with the message that says so instead of hanging.
cfg="$ROOT/tests/integration/configs/readers.yaml"
for tool in sbatch slurmctld slurmd munged; do
  command -v "$tool" >/dev/null ||
    fail "$tool is missing: install slurm-wlm and munge (./pbms test installs them)"
done
passed=0
ok() { echo "ok   $*"; passed=$((passed + 1)); }

# 1. Refused before anything is written.
mkdir bad && cd bad
sed 's/^launch: {md: 1,/launch: {md: -1,/' "$cfg" > bad.yaml
grep -q "md: -1" bad.yaml || fail "could not make the bad config"
set +e
"$PBMS" run --slurm bad.yaml > out.txt 2> err.txt
rc=$?
set -e
[ "$rc" -eq 1 ] || { cat out.txt err.txt; fail "--slurm with a bad config: exit $rc, not 1"; }
grep -qE '^bad\.yaml:[0-9]+:[0-9]+: error: launch\.md: ' err.txt ||
  { cat err.txt; fail "--slurm with a bad config: no file:line:col error for launch.md"; }
[ -z "$(find . -name '*.slurm*' -o -name job.sh)" ] || fail "--slurm wrote files for a bad config"
ok "a bad config is refused by --slurm: $(grep -m1 ': error: ' err.txt)"
cd ..

# 2. The reference: the same config through ./pbms run (mpirun).
mkdir mpirun && cd mpirun
"$PBMS" run "$cfg" > out.txt 2>&1 || { cat out.txt; fail "./pbms run"; }
cd ..

# 3. The batch script, and the job through sbatch.
mkdir slurm && cd slurm
"$PBMS" run --slurm "$cfg" > out.txt 2>&1 || { cat out.txt; fail "./pbms run --slurm"; }
job="$PWD/runs/readers.slurm/job.sh"
[ -x "$job" ] || { cat out.txt; fail "no $job"; }
[ ! -e runs/readers ] || fail "--slurm made the run directory; only the job may"
grep -qx '#SBATCH --ntasks=5' "$job" || fail "job.sh does not ask for 5 tasks"
for line in "0 env PBMS_APP=0 $ROOT/build/bin/coupler daemon $cfg" \
            "1 env PBMS_APP=1 $ROOT/build/bin/md_driver" \
            "2 env PBMS_APP=2 $ROOT/build/bin/dpd_driver" \
            "3-4 env PBMS_APP=3 $ROOT/build/bin/mpm_driver"; do
  grep -qF "$line" "$job" || { cat "$job"; fail "job.sh lacks the multi-prog line '$line'"; }
done
bash -n "$job" || fail "job.sh is not valid bash"
ok "job.sh asks for 5 tasks and starts 4 programs with PBMS_APP 0-3"

jobid=""
cleanup() {
  # Runs to its end even when ctest or a user interrupts the test meanwhile.
  trap '' INT TERM
  set +e
  if [ -n "$jobid" ] && [ -n "$(squeue -h -j "$jobid" 2>/dev/null)" ]; then
    scancel "$jobid"
    for _ in $(seq 1 30); do [ -z "$(squeue -h -j "$jobid" 2>/dev/null)" ] && break; sleep 1; done
  fi
  slurm_stop
}
trap cleanup EXIT
t0=$(date +%s)
slurm_start "$PWD/../cluster"
t1=$(date +%s)
echo "one-node Slurm up in $((t1 - t0)) s (SLURM_CONF=$SLURM_CONF)"

# wait_job ID SECONDS: until the job has left the queue; prints its state and exit code.
wait_job() {
  for _ in $(seq 1 "$2"); do
    [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && break
    sleep 1
  done
  [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] || { slurm_log_tail; fail "job $1 still queued or running after $2 s"; }
  scontrol show job "$1" | grep -oE '(JobState|ExitCode)=[^ ]+' | tr '\n' ' '
}
jobid="$(sbatch --parsable "$job")" || { slurm_log_tail; fail "sbatch $job"; }
state="$(wait_job "$jobid" 240)"
t2=$(date +%s)
slurm_out="runs/readers.slurm/slurm-$jobid.out"
echo "job $jobid: $state($((t2 - t1)) s)"
case "$state" in
  *JobState=COMPLETED*ExitCode=0:0*) ;;
  *) cat "$slurm_out" 2>/dev/null; slurm_log_tail; fail "the sbatch job ended as: $state" ;;
esac
[ -f runs/readers/summary.yaml ] || { cat "$slurm_out"; fail "the job wrote no summary.yaml"; }
grep -q "env PBMS_APP=3" "runs/readers.slurm/multi-prog-$jobid.conf" ||
  fail "the job did not leave its multi-prog file"
status="$(yget runs/readers/manifest.yaml status)"
[ "$status" = ok ] || fail "manifest status of the Slurm run: '$status'"
ok "sbatch job $jobid completed; manifest status ok"

# 4. Same results: every number of summary.yaml and every numeric dataset of
# the run's HDF5 files (results.h5, the H5MD trajectories and grids) to 1e-9
# relative, the same keys and datasets; only the timings (wall_s,
# steps_per_second, the exchange profiles' seconds and waiting fractions)
# may differ.
"$PY" - ../mpirun/runs/readers runs/readers <<'PYEOF' || fail "the runs differ"
import math, pathlib, re, sys
import h5py, numpy as np, yaml
ref, run = (pathlib.Path(p) for p in sys.argv[1:3])
TIMING = re.compile(r"(^|[./])(wall_s|steps_per_second|\w*seconds_\w+|\w*_waiting_fraction)($|[./])")
bad, n = [], 0
def walk(x, y, path):
    global n
    if TIMING.search(path):
        return
    if isinstance(x, dict) and isinstance(y, dict):
        if set(x) != set(y):
            bad.append(f"{path}: keys {sorted(set(x) ^ set(y))} in one only")
        for k in sorted(set(x) & set(y)):
            walk(x[k], y[k], f"{path}.{k}")
    elif isinstance(x, list) and isinstance(y, list):
        if len(x) != len(y):
            bad.append(f"{path}: {len(x)} items against {len(y)}")
        for i, (u, v) in enumerate(zip(x, y)):
            walk(u, v, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and isinstance(y, (int, float)):
        n += 1
        if x != y and not math.isclose(x, y, rel_tol=1e-9, abs_tol=0.0):
            bad.append(f"{path}: {x!r} (mpirun) against {y!r} (sbatch)")
    elif x != y:
        bad.append(f"{path}: {x!r} against {y!r}")
walk(yaml.safe_load(open(ref / "summary.yaml")), yaml.safe_load(open(run / "summary.yaml")),
     "summary")
n_summary = n
files = sorted(p.relative_to(ref) for p in ref.rglob("*") if p.suffix in (".h5", ".h5md"))
if [p.relative_to(run) for p in sorted(run.rglob("*")) if p.suffix in (".h5", ".h5md")] != files:
    bad.append("the runs wrote different HDF5 files")
n_sets = 0
for rel in files:
    with h5py.File(ref / rel, "r") as fa, h5py.File(run / rel, "r") as fb:
        names = []
        fa.visititems(lambda k, o: names.append(k) if isinstance(o, h5py.Dataset) else None)
        for k in names:
            if TIMING.search(k) or fa[k].dtype.kind not in "fiu":
                continue
            if k not in fb:
                bad.append(f"{rel}:{k}: missing from the sbatch run")
                continue
            a, b = fa[k][()], fb[k][()]
            n_sets += 1
            if np.shape(a) != np.shape(b):
                bad.append(f"{rel}:{k}: shapes {np.shape(a)} against {np.shape(b)}")
            elif not np.allclose(b, a, rtol=1e-9, atol=0.0, equal_nan=True):
                d = np.max(np.abs(np.asarray(a, float) - b) / np.maximum(np.abs(a), 1e-300))
                bad.append(f"{rel}:{k}: relative difference up to {d:.2e}")
for line in bad:
    print("FAIL", line)
print(f"{n_summary} numbers of summary.yaml and {n_sets} datasets in {len(files)} HDF5 files "
      f"compared, {len(bad)} differences (tolerance 1e-9 relative)")
sys.exit(1 if bad or n_summary == 0 or n_sets == 0 else 0)
PYEOF
ok "the sbatch job's summary.yaml and HDF5 files equal those of ./pbms run"

# 5. The same script submitted again finds the run directory taken: the job
# fails with the refusal and leaves the first run as it was.
before="$(cd runs/readers && find . -type f -exec md5sum {} + | sort)"
jobid="$(sbatch --parsable "$job")"
state="$(wait_job "$jobid" 120)"
case "$state" in
  *JobState=COMPLETED*) fail "a second job of the same run name completed" ;;
esac
grep -q "holds an earlier run" "runs/readers.slurm/slurm-$jobid.out" ||
  { cat "runs/readers.slurm/slurm-$jobid.out"; fail "no refusal in the second job's output"; }
[ "$(cd runs/readers && find . -type f -exec md5sum {} + | sort)" = "$before" ] ||
  fail "the second job changed the first run's files"
ok "a second submission is refused ($state) and leaves the first run unchanged"

# 6. Without PBMS_APP every process of an srun job reads MPI_APPNUM 0: the
# job must end at once with the message, not hang.
# (The MPI settings of lib.sh reach the job: sbatch passes the environment on.)
mkdir ../noapp && cd ../noapp
bin="$ROOT/build/bin"
printf '0 %s daemon %s\n1 %s\n' "$bin/coupler" "$cfg" "$bin/md_driver" > noapp.conf
jobid="$(sbatch --parsable --ntasks=2 --output="$PWD/slurm-%j.out" \
  --wrap="srun --mpi=pmix --kill-on-bad-exit=1 --multi-prog $PWD/noapp.conf")"
state="$(wait_job "$jobid" 60)"
case "$state" in
  *JobState=COMPLETED*) cat "slurm-$jobid.out"; fail "a job without PBMS_APP completed" ;;
esac
grep -q "have the same app number 0" "slurm-$jobid.out" ||
  { cat "slurm-$jobid.out"; fail "no 'same app number' message without PBMS_APP"; }
ok "without PBMS_APP the srun job ends ($state) with: $(grep -m1 -o 'world ranks.*app number 0' "slurm-$jobid.out")"

jobid=""
echo "$passed passed, 0 failed"
