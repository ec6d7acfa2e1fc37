source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# A time step above the CFL bound is refused with the bound printed; a
# point leaving the grid stops the run naming its id, position and step.
here="$(dirname "$0")/configs"
if "$PBMS" run "$here/mpm_cfl_too_large.yaml" > cfl.txt 2>&1; then fail "CFL-breaking run succeeded"; fi
grep -q "exceeds the CFL bound h / max(c + |v|) = 0.0025" cfl.txt || { cat cfl.txt; fail "CFL message"; }
grep -q "mpm_driver rank 0 failed in stage 'too_large'" cfl.txt || { cat cfl.txt; fail "CFL: stage"; }
if "$PBMS" run "$here/mpm_point_leaves.yaml" > leave.txt 2>&1; then fail "escaping point did not stop the run"; fi
grep -Eq "stage 'escape' at step [0-9]+: material point [0-9]+ left the grid at \(" leave.txt \
  || { cat leave.txt; fail "leaving message"; }
grep -m1 "left the grid" leave.txt
echo "2 passed, 0 failed"
