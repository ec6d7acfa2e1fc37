# Shared helpers for integration tests. Each test runs in its own working
# directory (set by ctest) and gets the repository root as $1.
set -euo pipefail
ROOT="$1"
shift
PBMS="$ROOT/pbms"
PY=/usr/bin/python3
# ctest runs on the tree `./pbms test` has just built: the launcher's own
# incremental build (0.7 s a call, some 70 calls in the default suite) is
# skipped. quickstart.sh clears this to run the README's command as a user.
export PBMS_SKIP_BUILD=1
# The Python checks import tests/integration/summary_checks.py.
export PYTHONPATH="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)${PYTHONPATH:+:$PYTHONPATH}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# As ./pbms runs its jobs (mpi_env there), for the tests' own plain `mpirun lmp`.
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none PMIX_MCA_gds=hash

fail() { echo "FAIL: $*" >&2; exit 1; }

# Reads a value from a YAML file: yget FILE key.path.with.dots
yget() {
  "$PY" - "$1" "$2" <<'PYEOF'
import sys, yaml
node = yaml.safe_load(open(sys.argv[1]))
for k in sys.argv[2].split('.'):
    node = node[int(k)] if isinstance(node, list) else node[k]
print(node)
PYEOF
}

# Waits (up to TRIES tenths of a second) until RUN_DIR's manifest shows stage
# STAGE at a step matching STEP_RE, failing if the job PID ends first:
#   wait_for_step RUN_DIR STAGE STEP_RE PID [TRIES]
wait_for_step() {
  local run=$1 stage=$2 step=$3 pid=$4 tries=${5:-600}
  for _ in $(seq 1 "$tries"); do
    if [ -f "$run/manifest.yaml" ] && grep -q "stage: $stage" "$run/manifest.yaml" &&
       grep -q "step: $step" "$run/manifest.yaml"; then return 0; fi
    kill -0 "$pid" 2>/dev/null || { cat out.txt err.txt; fail "job ended before the kill"; }
    sleep 0.1
  done
}

# The PID of this test's PROGRAM process (started from this directory; the
# mpirun command line matches pgrep too), with world rank WORLD_RANK when
# given; empty when there is none: job_process PROGRAM [WORLD_RANK]
job_process() {
  local program=$1 world=${2:-} p found=""
  for p in $(pgrep -f "build/bin/$program"); do
    [[ "$(readlink "/proc/$p/exe" 2>/dev/null)" == */$program ]] || continue
    [[ "$(readlink "/proc/$p/cwd" 2>/dev/null)" == "$PWD" ]] || continue
    if [ -z "$world" ] ||
       tr '\0' '\n' < /proc/$p/environ 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$world"; then
      found=$p
    fi
  done
  echo "$found"
}

# The pids of every program of this directory's job: the coupler and the
# drivers, every rank.
job_tasks() {
  local p
  for p in $(pgrep -f "build/bin/(coupler|dpd_driver|mpm_driver|md_driver)"); do
    [[ "$(readlink "/proc/$p/exe" 2>/dev/null)" =~ /(coupler|dpd_driver|mpm_driver|md_driver)$ ]] ||
      continue
    [[ "$(readlink "/proc/$p/cwd" 2>/dev/null)" == "$PWD" ]] && echo "$p"
  done
}

# SIGTERM to `./pbms run CONFIG` (TO = launcher, the default) or to every
# task of its job (TO = tasks) while it holds the checkpoint write PAUSE
# (NAME:SECONDS, so that the signal finds the stage running whatever the
# machine's speed) and FILE (that write's .partial) exists; the job must end
# non-zero within 10 s. Its output goes to OUT:
# stop_during_checkpoint CONFIG PAUSE FILE OUT [TO]
stop_during_checkpoint() {
  local config=$1 pause=$2 file=$3 out=$4 to=${5:-launcher} launcher t0
  PBMS_TEST_CHECKPOINT_PAUSE="$pause" "$PBMS" run "$config" > "$out" 2>&1 &
  launcher=$!
  for _ in $(seq 1 600); do
    [ -f "$file" ] && break
    kill -0 $launcher 2>/dev/null || { cat "$out"; fail "the job ended before the signal"; }
    sleep 0.1
  done
  t0=$(date +%s.%N)
  if [ "$to" = tasks ]; then
    # As Slurm's --signal does: every task of the job gets it, mpirun and
    # the launcher none.
    kill -TERM $(job_tasks)
  else
    kill -TERM $launcher
  fi
  timeout 10 tail --pid=$launcher -f /dev/null || fail "the job did not end within 10 s of SIGTERM"
  echo "  ended $(printf '%.1f' "$(echo "$(date +%s.%N) - $t0" | bc)") s after SIGTERM"
  ! wait $launcher || fail "the signalled job exited 0"
}
