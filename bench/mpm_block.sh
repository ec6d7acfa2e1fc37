#!/usr/bin/env bash
# MPM step throughput on one core (1,000,000 points, linear shape
# functions, 8 points per cell, best of two rounds of 100 steps) and its
# fraction of the memory roofline, for the native build and, side by side,
# the grid step built for AVX2 (x86-64-v3) and for SSE2 (x86-64), where
# the machine runs them (PBMS_ISA_VARIANTS in CMakeLists.txt). The builds
# take turns, two rounds each, and each reports its faster round.
#
# Prints BENCH mpm_particle_steps_per_s (target >= 5e6) and
# mpm_roofline_fraction (target >= 0.5) for the native build, the same
# with the suffix _x86_64_v3 or _x86_64 for the others (x86-64-v3: targets
# >= 5e6 and >= 0.45), and mpm_x86_64_v3_over_native, mpm_x86_64_over_native.
# Per pass, "# pass" lines say where the time goes. About 3 minutes.
set -euo pipefail
ROOT="$1"
BIN="$ROOT/build/bin"
builds=(native)
for v in x86_64_v3 x86_64; do
  [ -x "$BIN/mpm_block_bench_$v" ] && builds+=("$v")
done
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
for round in 1 2; do
  for b in "${builds[@]}"; do
    exe="$BIN/mpm_block_bench"
    [ "$b" = native ] || exe="$BIN/mpm_block_bench_$b"
    "$exe" >"$work/$b.$round"
  done
done
# Per build: the round with the higher rate, its comment lines and its
# BENCH lines, the latter suffixed with the build's name.
best_round() {
  local b="$1" best=1 r1 r2
  r1=$(awk '/^BENCH mpm_particle_steps_per_s/ {print $3}' "$work/$b.1")
  r2=$(awk '/^BENCH mpm_particle_steps_per_s/ {print $3}' "$work/$b.2")
  awk -v a="$r1" -v b="$r2" 'BEGIN {exit !(b > a)}' && best=2
  echo "$work/$b.$best"
}
declare -A rate
for b in "${builds[@]}"; do
  f="$(best_round "$b")"
  echo "# --- $b"
  grep '^#' "$f"
  suffix=""
  [ "$b" = native ] || suffix="_$b"
  awk -v s="$suffix" '/^BENCH/ {print $1, $2 s, $3, $4}' "$f"
  rate[$b]=$(awk '/^BENCH mpm_particle_steps_per_s/ {print $3}' "$f")
done
for b in "${builds[@]}"; do
  [ "$b" = native ] && continue
  awk -v v="${rate[$b]}" -v n="${rate[native]}" -v b="$b" \
    'BEGIN {printf "BENCH mpm_%s_over_native %.3f 1\n", b, v / n}'
done
