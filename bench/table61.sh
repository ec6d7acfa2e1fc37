#!/usr/bin/env bash
# The seed's Table 6.1, side by side on this machine: assembly 0 (two copper
# spheres) at 1 GPa on the concurrent DPD/MPM model of configs/sintering.yaml,
# but on the seed's grid and gas lattice of a_cg (the config's own grid is
# a_cg/2; docs/chapter6.md gives its cost), dpd_driver and mpm_driver a rank
# each; and LAMMPS MD of the same two spheres (EAM copper, Mishin 2001: all
# fcc atoms within 8 a of the same centres, 2 x 8,589 atoms, 298 K, NVT,
# 2 fs) with plain lmp on 2 ranks.
# Each runs a stretch and is scaled to the seed's 100 ps by its own step
# rate (PBMS: 10 ps of the pair; MD: 2 ps, at least what the issue asks).
# Prints, for 100 ps:
#   BENCH table61_wall_s, table61_cpu_s          (PBMS, both drivers)
#   BENCH table61_lammps_cpu_s
#   BENCH table61_speedup_vs_lammps               (LAMMPS CPU over PBMS CPU)
#   BENCH table61_peak_rss_mb_<program>           (each program's largest rank)
# The coupler's CPU is not counted: it waits on the drivers' messages.
# PBMS_GRID_MOVE=step_start runs the step-start move instead of the midpoint
# move (grid.move's default).
set -euo pipefail
ROOT="$1"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
PBMS_PS=10
MD_PS=2

PYTHONPATH="$ROOT/tests/integration" /usr/bin/python3 - "$ROOT/configs/sintering.yaml" "$PBMS_PS" "${PBMS_GRID_MOVE:-midpoint}" > pair.yaml <<'PY'
import sys
import yaml
import derived_config
config = derived_config.load(sys.argv[1])
config["run"] = {"name": "table61", "seed": 2026, "output": "runs"}
config["launch"] = {"dpd": 1, "mpm": 1}
config["stages"] = [s for s in config["stages"] if s["name"] in ("sphere", "pair_1GPa")]
for s in config["stages"]:
    if s["name"] == "pair_1GPa":
        # Table 6.1's model: the seed's grid and gas lattice of a_cg (the
        # config's own grid of a_cg/2 holds 224,444 gas points).
        s["grid"] = {"origin": [-3.615] * 3, "cell_size": 7.23, "cells": [31, 31, 31],
                     "move": sys.argv[3]}
        s["gas"]["spacing"] = 7.23
        s["steps"] = int(round(float(sys.argv[2]) / 0.01))
        s["particles_every"] = 0
        s["neck_stable_time"] = "2 ps"
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PY
"$ROOT/pbms" run pair.yaml > pbms.txt 2>&1 || { tail -30 pbms.txt; exit 1; }

# The same two spheres in LAMMPS, each of the atoms within 8 a of an atomic
# lattice site, their outermost atoms 7.23 Å apart along the line through
# the centres, as the DPD spheres' outermost particles are: centres 65.07 Å
# apart (22 a and 40 a). Closer, as the DPD spheres' centres (58.55 Å),
# the atomic spheres of 8 a would overlap.
cat > pair.in <<'LMP'
units metal
atom_style atomic
boundary s s s
lattice fcc 3.615
region box block 0 216.9 0 216.9 0 216.9 units box
create_box 1 box
region left sphere 79.53 108.45 108.45 28.92 units box
region right sphere 144.6 108.45 108.45 28.92 units box
create_atoms 1 region left
create_atoms 1 region right
mass 1 63.546
pair_style eam/alloy
pair_coeff * * /usr/share/lammps/potentials/Cu_mishin1.eam.alloy Cu
velocity all create 298 2026 mom yes rot yes
fix nvt all nvt temp 298 298 0.1
timestep 0.002
thermo 100
LMP
echo "run $(( MD_PS * 500 ))" >> pair.in
/usr/bin/time -f "%e %U %S %M" -o lmp_time.txt mpirun -np 2 lmp -in pair.in -log lmp.log -screen none -nocite

/usr/bin/python3 - "$PBMS_PS" "$MD_PS" <<'PY'
import sys
import h5py
pbms_ps, md_ps = float(sys.argv[1]), float(sys.argv[2])
with h5py.File("runs/table61/results.h5", "r") as f:
    g = f["pair_1GPa"]
    attr = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
    wall = float(attr["wall_s"])
    cpu = {p: float(attr[f"cpu_s.{p}"]) for p in ("dpd_driver", "mpm_driver")}
    rss = {p: float(attr[f"peak_rss_mb.{p}"]) for p in ("dpd_driver", "mpm_driver")}
    dpd, gas = int(g["dpd_particles"][()]), int(g["gas_points"][()])
atoms = 0
for line in open("lmp.log"):
    if line.startswith("Created") and "atoms" in line:
        atoms += int(line.split()[1])
lmp_wall, lmp_user, lmp_sys, lmp_rss_kb = map(float, open("lmp_time.txt").read().split())
energies = [line.split()[2] for line in open("lmp.log") if line.split()[:1] and line.split()[0].isdigit()]
if not energies or any(e.lower() in ("nan", "-nan", "inf", "-inf") for e in energies):
    sys.exit(f"LAMMPS' run is not sound (pair energies {energies[:3]} ...)")
scale_pbms, scale_md = 100.0 / pbms_ps, 100.0 / md_ps
pbms_cpu = sum(cpu.values()) * scale_pbms
lammps_cpu = (lmp_user + lmp_sys) * scale_md
print(f"PBMS: {dpd} DPD particles and {gas} gas points, {pbms_ps:g} ps in {wall:.1f} s "
      f"(CPU {cpu['dpd_driver']:.1f} s dpd_driver, {cpu['mpm_driver']:.1f} s mpm_driver)")
print(f"LAMMPS: {atoms} atoms, {md_ps:g} ps in {lmp_wall:.1f} s (CPU {lmp_user + lmp_sys:.1f} s on 2 ranks)")
print(f"BENCH table61_wall_s {wall * scale_pbms:.1f} s")
print(f"BENCH table61_cpu_s {pbms_cpu:.1f} s")
print(f"BENCH table61_lammps_wall_s {lmp_wall * scale_md:.1f} s")
print(f"BENCH table61_lammps_cpu_s {lammps_cpu:.1f} s")
print(f"BENCH table61_speedup_vs_lammps {lammps_cpu / pbms_cpu:.3f} 1")
for p, v in rss.items():
    print(f"BENCH table61_peak_rss_mb_{p} {v:.1f} MB")
print(f"BENCH table61_peak_rss_mb_lammps {lmp_rss_kb / 1024.0:.1f} MB")
PY
