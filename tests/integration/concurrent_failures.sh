source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# Failures in a concurrent DPD/MPM stage end the whole job, never hang:
# SIGKILL of an mpm_driver rank and of the dpd_driver rank mid-stage each end
# it within 10 s, non-zero, naming the program, rank, stage and step; a
# material point that inverts (an MPM time step far above its CFL bound),
# a DPD flyer launched off the grid, MPM points pulled off the grid and DPD
# particles whose forces overflow each stop both programs within seconds,
# with a message naming the program, particle, step and part of the body.
CONFIG="$(dirname "$0")/configs/concurrent_small.yaml"

kill_one() {  # PROGRAM WORLD_RANK EXPECTED_PROGRAM_RANK
  local program=$1 world=$2 expect=$3
  rm -rf runs
  # A bar at rest (the flyer still): it runs until killed, not off the grid.
  sed 's/steps: 300/steps: 200000/; s/velocity: \[5, 0, 0\]/velocity: [0, 0, 0]/' "$CONFIG" > long.yaml
  "$PBMS" run long.yaml > out.txt 2> err.txt &
  local pid=$! run=runs/concurrent_small victim
  wait_for_step "$run" impact "[1-9]" $pid
  victim=$(job_process "$program" "$world")
  [ -n "$victim" ] || fail "no $program process with world rank $world found"
  local start rc=0 elapsed
  start=$(date +%s.%N)
  kill -9 "$victim"
  wait $pid || rc=$?
  elapsed=$("$PY" -c "import time; print(round($(date +%s.%N) - $start, 2))")
  echo "killed $program (world rank $world): exit code $rc after ${elapsed}s"
  grep "error\|failed" err.txt | head -2 || true
  [ "$rc" -ne 0 ] || fail "job exited 0 after $program was killed"
  "$PY" -c "import sys; sys.exit(0 if $elapsed < 10 else 1)" || fail "job took ${elapsed}s to end"
  grep -q "$program rank $expect" err.txt || fail "message does not name $program rank $expect"
  grep -q "stage 'impact'" err.txt || fail "message does not name the stage"
  grep -q "step [1-9]" err.txt || fail "message does not name the step"
}

fails_with() {  # NAME SED_EXPRESSION EXPECTED_TEXT REGIONS_TEXT
  local name=$1 edit=$2 expect=$3 rc=0 start elapsed
  sed "$edit; s/name: concurrent_small/name: $name/" "$CONFIG" > "$name.yaml"
  start=$(date +%s.%N)
  timeout 120 "$PBMS" run "$name.yaml" > out.txt 2> err.txt || rc=$?
  elapsed=$("$PY" -c "import time; print(round($(date +%s.%N) - $start, 2))")
  echo "$name: exit code $rc after ${elapsed}s"
  grep "error\|failed" err.txt | head -2 || true
  [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "$name: exit code $rc (124: it hung)"
  "$PY" -c "import sys; sys.exit(0 if $elapsed < 30 else 1)" || fail "$name: took ${elapsed}s to end"
  grep -q "$expect" err.txt || fail "$name: message does not say '$expect'"
  grep -q "step [0-9]" err.txt || fail "$name: message does not name the step"
  grep -q "$4" err.txt || fail "$name: message does not name the part's regions ('$4')"
}

# World ranks: 0 coupler, 1 dpd_driver, 2 and 3 mpm_driver.
kill_one mpm_driver 3 1
kill_one dpd_driver 1 0
# The stiffest solid validation lets through (2,000 GPa) at nearly
# incompressible nu = 0.49: the P-wave crosses 1.5 cells a step. (The
# 9.1e7 GPa this case used is refused before the job starts since issue 33.)
fails_with mpm_unstable 's/youngs_modulus: 91 GPa, poisson_ratio: 0.35/youngs_modulus: 2000 GPa, poisson_ratio: 0.49/' "mpm_driver rank [01] in stage 'impact' at step" \
  "in the MPM part (region 'right')"
fails_with dpd_off_grid 's/velocity: \[5, 0, 0\]/velocity: [-3000, 0, 0]/' "dpd_driver rank 0 in stage 'impact' at step" \
  "in the DPD part (region 'left' and particles in no region)"
# A rigid group at the MPM end pulled off the grid at 10 Å a step: before
# the collective HDF5 close was skipped while an exception unwinds, the
# failing mpm_driver rank closed its H5MD file and waited for the other
# rank, which was migrating points: a hang.
fails_with mpm_off_grid 's/    groups:/    groups:\n      - {name: mpm_end, region: {style: block, lo: [110, 0, 0], hi: [116, 28.92, 28.92]}}/;
  s/      - {group: flyer, kind: rigid_body, velocity: \[5, 0, 0\]}/&\n      - {group: mpm_end, kind: rigid, velocity: [1000, 0, 0]}/' \
  "mpm_driver rank [01] in stage 'impact' at step [0-9]*: material point [0-9]* left the grid" \
  "in the MPM part (region 'right')"
# DPD pair forces that overflow (a Morse well of 1e308 eV) at the first
# step. Overlapping bodies, which made them NaN before, are refused before
# the job starts since issue 33. The infinite forces reach the MPM points
# through the grid in the same step, so both programs find non-finite values
# at step 1 and either may end the job first (CI has seen both): whichever
# does must name its own part.
fails_with dpd_inf_forces 's/d0: 2.70736/d0: 1.0e308/' \
  "rank [01] in stage 'impact' at step 1: .*non-finite" \
  "in the \(MPM\|DPD\) part"
if grep -q "mpm_driver rank [01] in stage 'impact' at step 1: .*non-finite" err.txt; then
  grep -q "in the MPM part (region 'right')" err.txt || fail "dpd_inf_forces: mpm_driver's message does not name region 'right'"
else
  grep -q "dpd_driver rank 0 in stage 'impact' at step 1: .*non-finite.*in the DPD part (region 'left'" err.txt ||
    fail "dpd_inf_forces: dpd_driver's message does not name its particle, step and region 'left'"
fi
echo "1 passed, 0 failed"
