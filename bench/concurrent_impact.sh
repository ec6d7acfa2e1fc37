#!/usr/bin/env bash
# The cost of a concurrent DPD/MPM run split across two programs against the
# same model in one process, and against the same target all DPD
# (bench/concurrent_impact_bench.cpp). Two ranks, one core each.
set -euo pipefail
ROOT="$1"
mpirun -np 2 --oversubscribe "$ROOT/build/bin/concurrent_impact_bench"
