#!/usr/bin/env bash
# The measured inputs of the scaling model (docs/scaling.md), on this machine:
# what a step costs per DPD particle, per MPM point and per gas point, and
# how many bytes the two programs exchange a step per unit of interface
# area. A bar at rest, half DPD and half MPM (the momentum-conserving
# interface), periodic across, one rank per program, at two cross-sections
# (6 x 6 and 12 x 12 a_cg: 4x the interface area, 4x the particles); and the
# inclusion's cube in a 1 GPa gas for the gas points. A part's compute time
# is the stepping time (steps over steps_per_second) less its wait for the
# other program (*_exchange_waiting_fraction): its CPU time would count the
# MPI wait, which spins. The gas figure holds the grid's nodes too (the
# cube itself is all DPD).
# Prints:
#   BENCH scaling_dpd_us_per_particle_step, scaling_mpm_us_per_point_step,
#         scaling_gas_us_per_point_step            (µs of compute on one core)
#   BENCH scaling_exchange_bytes_per_area_step      (bytes/Å² a step, both directions)
#   BENCH scaling_exchange_bytes_per_step_<w>       (each cross-section)
#   BENCH scaling_wait_fraction_<w>                 (the waiting part of a step)
#   BENCH scaling_gas_exchange_bytes_per_particle_step (in a gas the band is
#         the body's box: bytes a step per DPD particle of the cube)
# PBMS_GRID_MOVE=step_start measures the step-start move instead of the
# midpoint move (grid.move's default).
set -euo pipefail
ROOT="$1"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
STEPS=1000

/usr/bin/python3 - "$ROOT/configs/inclusion_in_gas.yaml" "$STEPS" "${PBMS_GRID_MOVE:-midpoint}" > scaling.yaml <<'PY'
import sys
import yaml
steps = int(sys.argv[2])
material = {"kind": "dpd_mesoparticle", "mass": 508.37, "lattice_constant": 7.23,
            "potential": {"style": "morse", "d0": 2.70736, "alpha": 0.740826, "r0": 5.472809,
                          "cutoff": 10, "shift": True}}
a = 7.23
stages = []
for cells in (6, 12):
    w, length = cells * a, 24 * a
    stages.append({
        "name": f"bar_{cells}", "kind": "concurrent", "material": "cu_cg",
        "box": {"lo": [-a, 0, 0], "hi": [length + a, w, w], "periodic": ["y", "z"]},
        "bodies": [{"name": "bar", "region": {"style": "block", "lo": [0, 0, 0], "hi": [length, w, w]}}],
        "temperature": 298, "gamma": 0.2, "bath_temperature": 298,
        "regions": [
            {"name": "dpd_half", "solver": "dpd", "region": {"style": "block", "lo": [-1, 0, 0], "hi": [length / 2 - 0.9, w, w]}},
            {"name": "mpm_half", "solver": "mpm", "region": {"style": "block", "lo": [length / 2 - 0.9, 0, 0], "hi": [length + 1, w, w]}}],
        "grid": {"origin": [-3 * a, 0, 0], "cell_size": a, "cells": [30, cells, cells]},
        "interface": "momentum_conserving",
        "continuum": {"youngs_modulus": "65 GPa", "poisson_ratio": 0.42},
        "steps": steps, "sample_every": 50, "particles_every": 0})
# The gas: the inclusion's cube in its 1 GPa gas, from the cube alone.
inclusion = yaml.safe_load(open(sys.argv[1]))
by_name = {s["name"]: s for s in inclusion["stages"]}
# The cube keeps this bench's Morse model, which its figures were measured with.
cube = dict(by_name["cube"], steps=500, material="cu_cg")
gas = next(s for s in inclusion["stages"] if s.get("gas", {}).get("pressure") == "1 GPa")
gas = dict(gas, name="cube_in_gas", steps=steps, particles_every=0, material="cu_cg")
for key in ("volume",):
    gas.pop(key, None)
gas["grid"] = dict(gas["grid"])
for s in stages + [gas]:
    s["grid"]["move"] = sys.argv[3]
config = {"run": {"name": "scaling", "seed": 2026, "output": "runs"},
          "launch": {"dpd": 1, "mpm": 1},
          "materials": {"cu_cg": material},
          "stages": stages + [cube, gas]}
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PY
"$ROOT/pbms" run scaling.yaml > scaling.txt 2>&1 || { tail -30 scaling.txt; exit 1; }

/usr/bin/python3 - "$STEPS" <<'PY'
import sys
import h5py
steps = int(sys.argv[1])
a = 7.23
with h5py.File("runs/scaling/results.h5", "r") as f:
    def stage(name):
        g = f[name]
        attr = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in g.attrs.items()}
        val = lambda k: float(g[k][()]) if k in g else 0.0
        return attr, val
    bars = {}
    for cells in (6, 12):
        attr, val = stage(f"bar_{cells}")
        # A part's compute: the stepping time less its wait for the other
        # (an MPI wait spins, so CPU time counts the waiting too).
        wall = steps / val("steps_per_second")
        bars[cells] = dict(
            dpd_cpu=wall * (1.0 - val("dpd_exchange_waiting_fraction")),
            mpm_cpu=wall * (1.0 - val("mpm_exchange_waiting_fraction")),
            dpd=val("dpd_particles"), mpm=val("mpm_points"),
            bytes=val("dpd_exchange_bytes_per_step"),  # sent and received: the traffic
            wait=max(val("dpd_exchange_waiting_fraction"), val("mpm_exchange_waiting_fraction")),
            area=(cells * a) ** 2)
    attr, val = stage("cube_in_gas")
    gas_cpu = steps / val("steps_per_second") * (1.0 - val("mpm_exchange_waiting_fraction"))
    gas_points = val("gas_points")
    gas_bytes, cube = val("dpd_exchange_bytes_per_step"), val("dpd_particles")
big = bars[12]
for cells, b in bars.items():
    print(f"bar {cells}x{cells}: {b['dpd']:.0f} DPD particles ({b['dpd_cpu']:.2f} s compute), "
          f"{b['mpm']:.0f} MPM points ({b['mpm_cpu']:.2f} s compute), {b['bytes']:.0f} bytes a step, "
          f"interface {b['area']:.0f} Å²")
print(f"cube in gas: {gas_points:.0f} gas points, mpm_driver {gas_cpu:.2f} s compute; "
      f"{cube:.0f} DPD particles, {gas_bytes:.0f} bytes a step")
us = 1e6 / steps
print(f"BENCH scaling_dpd_us_per_particle_step {big['dpd_cpu'] * us / big['dpd']:.3f} us")
print(f"BENCH scaling_mpm_us_per_point_step {big['mpm_cpu'] * us / big['mpm']:.3f} us")
print(f"BENCH scaling_gas_us_per_point_step {gas_cpu * us / gas_points:.3f} us")
print(f"BENCH scaling_exchange_bytes_per_area_step {big['bytes'] / big['area']:.2f} B/A^2")
# With a gas the band is the body's whole box, not its surface: bytes a step
# per DPD particle (each fills a³/4 of the box).
print(f"BENCH scaling_gas_exchange_bytes_per_particle_step {gas_bytes / cube:.1f} B")
for cells, b in bars.items():
    print(f"BENCH scaling_exchange_bytes_per_step_{cells} {b['bytes']:.0f} B")
    print(f"BENCH scaling_wait_fraction_{cells} {b['wait']:.3f} 1")
PY
