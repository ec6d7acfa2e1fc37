#!/usr/bin/env bash
# MPM step throughput on one core (1,000,000 points, linear shape
# functions, 8 points per cell, best of two rounds of 100 steps) and its
# fraction of the memory roofline. Prints BENCH mpm_particle_steps_per_s
# (target >= 5e6) and BENCH mpm_roofline_fraction (target >= 0.5).
set -euo pipefail
ROOT="$1"
exec "$ROOT/build/bin/mpm_block_bench"
