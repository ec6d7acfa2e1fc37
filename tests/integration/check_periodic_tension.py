"""Checks a laterally periodic md_tension stage against the elastic constants
an md_elastic stage measured at the same temperature and lattice constant.

- The lateral faces are stress free: the slope of (sigma_yy + sigma_zz)/2
  against the axial strain below 1 GPa, and its mean over the fit window
  within 0.05 GPa of zero. A crystal held laterally would show a slope of
  C12 (about 120 GPa); a slope k leaves Young's modulus off by
  2 C12 k / (C11 + C12), about 0.84 k, so 1 GPa is 1.4 % of E at most. A
  constant lateral stress p shifts the curve and changes its slope only
  through the pressure derivative of the moduli (of order B' = 4), so
  0.05 GPa moves E by ~0.2 GPa (0.3 %); it would catch a barostat holding
  the wrong pressure. (Over a window centred on zero strain the mean alone
  would not show a laterally held crystal, hence the slope.)
- Young's modulus within 5 % of E<100> = (C11 - C12)(C11 + 2 C12)/(C11 + C12)
  from C11 and C12 at that temperature (isothermal on both sides: the
  thermostat acts in ~0.1 ps, the pull over 10 ps or more). The tolerance
  covers the statistical errors of both, which the configs keep to about
  1 % together (see the comments there), and the 0.1 % of the central
  differences at 2 % strain.

usage: check_periodic_tension.py RUN_DIR TENSION_STAGE ELASTIC_STAGE
"""
import sys

import h5py
import numpy as np
import yaml

run, tension, elastic = sys.argv[1:4]
stages = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
r, c = stages[tension]["results"], stages[elastic]["results"]
E, dE = r["youngs_modulus"]["value"], r["youngs_modulus"]["std_error"]
c11, c12 = c["c11_at_t"]["value"], c["c12_at_t"]["value"]
E100 = (c11 - c12) * (c11 + 2 * c12) / (c11 + c12)
fit_max = float(next(s for s in yaml.safe_load(open(f"{run}/config.yaml"))["stages"]
                     if s["name"] == tension)["fit_max_strain"])
with h5py.File(f"{run}/results.h5") as f:
    g = f[f"{tension}/stress_strain"]
    strain, lateral = g["strain"][:], 0.5 * (g["stress_yy"][:] + g["stress_zz"][:])
    temperature = g["temperature"][:]
sel = strain <= fit_max
k = np.polyfit(strain[sel], lateral[sel], 1)[0]
mean_lateral = r["lateral_stress"]["value"]
bad = 0


def check(ok, what):
    global bad
    bad += not ok
    print(("ok   " if ok else "FAIL ") + what)


check(abs(mean_lateral) < 0.05 and abs(k) < 1.0,
      f"{tension}: lateral stress {mean_lateral * 1e3:.2f} MPa on average over strains "
      f"{strain[sel][0]:.4f} to {fit_max}, slope {k:.2f} GPa per unit strain "
      f"(tolerances 50 MPa and 1 GPa)")
rel = abs(E - E100) / E100
check(rel <= 0.05,
      f"{tension}: laterally periodic, stress-free tension E = {E:.2f} ± {dE:.2f} GPa (block "
      f"error) at {temperature.mean():.0f} K; E<100> from {elastic}'s C11 = {c11:.2f}, "
      f"C12 = {c12:.2f} GPa: {E100:.2f} GPa; difference {100 * rel:.1f} % (tolerance 5 %)")
sys.exit(1 if bad else 0)
