source "$(dirname "$0")/lib.sh"
# The seed's nanowire (Table 3.1: 100.9 GPa at 10 K, 85.11 GPa at 300 K),
# configs/md_nanowire_table31.yaml: the 40a x 10a x 10a [100] copper wire
# on the seed's protocol with EAM and Sutton-Chen copper at 10 K and 300 K
# (validation, about 25 minutes). Prints each wire's E as md_tension
# measures it and under the other definitions the seed might have used:
# the cross-section of the relaxed wire's outermost atom centres, those
# plus half a plane spacing, the gauge's atoms times a^3/4 as the virial
# volume, the strain over the whole wire (grips included) instead of the
# gauge, and the fit windows 0-0.5 %, 0-1 % and 1-2 %. Asserted, as what
# the runs show (docs/md-driver.md):
# - each wire is softer at 300 K than at 10 K (Sutton-Chen by 14 standard
#   errors on seed 2026, EAM by 3.0: the ordering is asserted, the margin
#   printed);
# - starting the EAM wire at rest (the grips at full speed) instead of on
#   the grips' velocity profile changes its E by less than 3 standard errors;
# - no definition above brings a wire within 10 % of the seed's figure.
"$PBMS" run "$ROOT/configs/md_nanowire_table31.yaml" > run.txt 2>&1 || { cat run.txt; fail "nanowire runs"; }
"$PY" - <<'PYEOF'
import math

import h5py
import numpy as np
import yaml
from summary_checks import Checks

checks = Checks()
check = checks.check
run = "runs/md_nanowire_table31"
stages = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
results = h5py.File(f"{run}/results.h5", "r")
SEED = {10: 100.9, 300: 85.11}  # GPa, Table 3.1
CELLS, GRIP = (40, 10, 10), 2


def value(stage, key):
    return stages[stage]["results"][key]["value"]


def slope(x, y, lo, hi):
    m = (x >= lo) & (x <= hi)
    return np.polyfit(x[m], y[m], 1)[0]


def definitions(stage, a):
    """E (GPa) as measured, then under the other definitions."""
    E = value(stage, "youngs_modulus")
    with h5py.File(f"{run}/{stage}/tension.h5md", "r") as f:
        x = f["particles/all/position/value"][5]  # the relaxed wire as the pull starts (10 ps)
    lo, hi = x[:, 0].min(), x[:, 0].max()
    mid = np.abs(x[:, 0] - 0.5 * (lo + hi)) < 0.3 * (hi - lo)
    extent = []
    for k in (1, 2):
        y = x[mid, k]
        extent.append(y[y > y.max() - a / 4].mean() - y[y < y.min() + a / 4].mean())
    nominal = CELLS[1] * a * CELLS[2] * a
    gauge_length = (hi - lo) - 2 * GRIP * a
    gauge_atoms = ((x[:, 0] > lo + GRIP * a + 0.1) & (x[:, 0] < hi - GRIP * a - 0.1)).sum()
    s = results[stage]["stress_strain"]
    eps, sig = s["strain"][:], s["stress"][:]
    return {
        "md_tension": E,
        "atom centres": E * nominal / (extent[0] * extent[1]),
        "centres + a/2": E * nominal / ((extent[0] + a / 2) * (extent[1] + a / 2)),
        "atoms x a^3/4": E * nominal * gauge_length / (gauge_atoms * a**3 / 4),
        "whole-wire strain": E * (hi - lo) / gauge_length,
        "0-0.5 %": slope(eps, sig, 0.0, 0.005),
        "0-1 %": slope(eps, sig, 0.0, 0.01),
        "1-2 %": slope(eps, sig, 0.01, 0.02),
    }


sc_300K_a = value("sc_isotherm", "lattice_parameter")
wires = {("EAM", 10): ("eam_10K", 3.615), ("EAM", 300): ("eam_300K", 3.6317),
         ("Sutton-Chen", 10): ("sc_10K", 3.61), ("Sutton-Chen", 300): ("sc_300K", sc_300K_a)}
bulk = {"EAM": value("eam_bulk", "youngs_modulus_100"), "Sutton-Chen": value("sc_bulk", "youngs_modulus_100")}
for (potential, T), (stage, a) in wires.items():
    d = definitions(stage, a)
    err = stages[stage]["results"]["youngs_modulus"]["std_error"]
    grip = value(stage, "youngs_modulus_grip_force")
    print(f"info {potential} {T} K: E {d['md_tension']:.1f} ± {err:.1f} GPa (grip forces {grip:.1f}), "
          f"bulk E<100> at 0 K {bulk[potential]:.1f}, seed {SEED[T]}")
    print("info    " + ", ".join(f"{k} {v:.1f}" for k, v in d.items()))
    best = max(d.values())
    check(best < 0.9 * SEED[T], f"{potential} {T} K: no definition reaches within 10 % of the seed's "
          f"{SEED[T]} GPa (highest {best:.1f} GPa)")
for potential in ("EAM", "Sutton-Chen"):
    cold, hot = wires[(potential, 10)][0], wires[(potential, 300)][0]
    e = [stages[s]["results"]["youngs_modulus"] for s in (cold, hot)]
    sigma = math.hypot(e[0]["std_error"], e[1]["std_error"])
    drop = e[0]["value"] - e[1]["value"]
    check(drop > 0, f"{potential}: the wire softens from {e[0]['value']:.1f} GPa at 10 K to "
          f"{e[1]['value']:.1f} at 300 K ({drop / sigma:.1f} standard errors)")
p, r = (stages[s]["results"]["youngs_modulus"] for s in ("eam_300K", "eam_300K_from_rest"))
sigma = math.hypot(p["std_error"], r["std_error"])
check(abs(p["value"] - r["value"]) < 3 * sigma,
      f"EAM 300 K: started at rest {r['value']:.1f} GPa, on the velocity profile {p['value']:.1f} GPa "
      f"(within 3 standard errors, {3 * sigma:.1f} GPa): the start is not the gap")
checks.exit()
PYEOF
