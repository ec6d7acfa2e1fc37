#!/usr/bin/env bash
# The exchanges across programs on this machine (bench/coupling_exchange_bench.cpp):
# latency and bandwidth between two programs, and the per-step cost of the
# nodal sums and the ghost exchange of a concurrent-impact rod, on 1+1 and
# 2+2 ranks (oversubscribed where the machine has fewer cores).
set -euo pipefail
ROOT="$1"
for np in 2 4; do
  echo "# $((np / 2))+$((np / 2)) ranks"
  mpirun -np "$np" --oversubscribe "$ROOT/build/bin/coupling_exchange_bench"
done
