source "$(dirname "$0")/lib.sh"
# The coupler's scheduler with a real dpd_driver on 2 ranks: rank groups
# serving requests side by side, a failed request that leaves the driver in
# service, and answers that do not depend on the groups
# (tests/mpi/test_scheduler.cpp). The MPI settings are the launcher's.
BIN="$1"
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none PMIX_MCA_gds=hash
cfg="$ROOT/tests/integration/configs/scheduler_isotherm.yaml"
timeout 240 mpirun -np 1 "$BIN/pbms_scheduler_test" "$cfg" : -np 2 "$BIN/dpd_driver" ||
  fail "scheduler tests (exit $?)"
