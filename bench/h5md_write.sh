#!/usr/bin/env bash
# One H5MD frame of 100,000 DPD particles on 2 ranks (bench/h5md_write_bench.cpp):
# gathered on rank 0 and written there (the way before) against written
# collectively by every rank from the particles it holds.
set -euo pipefail
ROOT="$1"
mpirun -np 2 --oversubscribe "$ROOT/build/bin/h5md_write_bench"
