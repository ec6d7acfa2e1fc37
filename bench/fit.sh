#!/usr/bin/env bash
# The fit's judge: copper Sutton-Chen mesoparticles at 298 K, every candidate
# judged on its isotherm (7 pressures) and elastic constants. The same 8
# candidates (CRS2 with a fixed budget and seed, no local polish) on
# dpd_driver with one rank (one group) and with two ranks (two one-rank
# groups), one after the other in one run.
# Prints BENCH fit_evaluations_per_s (one group) and BENCH fit_group_speedup
# (target >= 1.7 on two cores).
set -euo pipefail
ROOT="$1"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
cat > fit.yaml <<YAML
run: {name: bench_fit, seed: 7}
materials:
  cu_sc:
    kind: dpd_mesoparticle
    mass: 508.37
    lattice_constant: 7.23
    potential: {style: sutton_chen, epsilon: 0.099056, a: 7.23, n: 9, m: 6, c: 39.432, cutoff: 11.8}
stages:
  - name: targets
    kind: dpd_isotherm
    material: cu_sc
    temperature: 298
    zero_pressure: false
    sampling_steps: 1000
    pressures: [0, 1 GPa, 2 GPa, 4 GPa, 6 GPa, 8 GPa, 10 GPa]
  - {name: elastic, kind: dpd_elastic, material: cu_sc, temperature: 298, sampling_steps: 1000}
  - name: fit
    kind: fit_dpd_potential
    material: cu_sc
    temperature: 298
    isotherm: {table: {from: targets.isotherm}}
    elastic: {c11: {from: elastic.c11}, c12: {from: elastic.c12}, c44: {from: elastic.c44}}
    free: {epsilon: [0.08, 0.12], c: [33, 45], n: [8, 10]}
    optimizer: {global: crs2_lm, local: none, global_evaluations: 8}
    judge: {sampling_steps: 1000}
    group_ranks: 1
YAML
wall() { /usr/bin/python3 -c "import yaml; s = yaml.safe_load(open('runs/bench_fit/summary.yaml'))['stages']['fit']; print(s['wall_s'], s['results']['evaluations']['value'])"; }
"$ROOT/pbms" run fit.yaml --ranks dpd=1 > one.txt 2>&1 || { cat one.txt; exit 1; }
one=$(wall)
# The same run name again, on two ranks: replacing the one-rank run is intended.
"$ROOT/pbms" run fit.yaml --ranks dpd=2 --overwrite > two.txt 2>&1 || { cat two.txt; exit 1; }
two=$(wall)
/usr/bin/python3 - $one $two <<'PY'
import sys
one, n, two, n2 = map(float, sys.argv[1:])
assert n == n2
# 8 search candidates and one more per free parameter for their errors.
print(f"{n:.0f} candidates: one group {one:.2f} s, two groups {two:.2f} s")
print(f"BENCH fit_evaluations_per_s {n / one:.3f} 1/s")
print(f"BENCH fit_group_speedup {one / two:.3f} 1")
PY
