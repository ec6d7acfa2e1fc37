"""The fitted crystal against MD (issue 32, "The fit"): every volume per
atom, held-out rows included, within 0.5 % of MD's; the moduli of the cubic
modes B, C' and C44 within 5 % and E<100> within 3 %, each recomputed here
from both sides' C11, C12 and C44 at the fit's temperature (dpd_elastic of
the fitted model against md_elastic's *_at_t). Used by hierarchy.sh
(copper) and fit_second_metal.sh (nickel) on a finished run directory.

    check_fit_against_md.py RUN_DIR [FIT_STAGE [MD_ELASTIC_STAGE [DPD_ELASTIC_STAGE]]]
"""
import sys

import h5py
import yaml

from summary_checks import Checks

TOLERANCES = {"B": 0.05, "C'": 0.05, "C44": 0.05, "E<100>": 0.03}


def moduli(c11, c12, c44):
    b, shear = (c11 + 2 * c12) / 3, (c11 - c12) / 2
    return {"B": b, "C'": shear, "C44": c44, "E<100>": 9 * b * shear / (3 * b + shear)}


def check_fit(c, run, fit="fit", md_stage="elastic_md", dpd_stage="elastic_dpd"):
    s = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
    with h5py.File(f"{run}/results.h5") as f:
        g = f[f"{fit}/isotherm"]
        rows = zip(g["pressure"][:], g["volume_per_atom_target"][:], g["volume_per_atom"][:],
                   g["held_out"][:])
        worst = 0.0
        for p, vt, v, held in rows:
            r = v / vt - 1
            worst = max(worst, abs(r))
            print(f"     {p / 1e4:5.1f} GPa{' (held out)' if held else '           '}: "
                  f"V_DPD {v:.4f} vs V_MD {vt:.4f} A^3 ({100 * r:+.3f} %)")
    c.check(worst <= 0.005, f"volume per atom within 0.5 % of MD's at every pressure (worst {100 * worst:.3f} %)")
    md, dpd = s[md_stage]["results"], s[dpd_stage]["results"]
    mm = moduli(*(md[f"{k}_at_t"]["value"] for k in ("c11", "c12", "c44")))
    dm = moduli(*(dpd[k]["value"] for k in ("c11", "c12", "c44")))
    for k, tol in TOLERANCES.items():
        r = dm[k] / mm[k] - 1
        c.check(abs(r) <= tol, f"{k} at the fit's temperature: DPD {dm[k]:.2f} vs MD {mm[k]:.2f} GPa "
                f"({100 * r:+.1f} %, tolerance {100 * tol:.0f} %)")
    return s


if __name__ == "__main__":
    checks = Checks()
    check_fit(checks, *sys.argv[1:])
    checks.exit()
