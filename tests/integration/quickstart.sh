source "$(dirname "$0")/lib.sh"
# The README's first command, as a user runs it: configs/quickstart.yaml,
# the whole method small (MD -> Sutton-Chen fit -> the fitted model's
# elastic constants -> a concurrent DPD/MPM impact). Asserted, each against
# a reference the DPD and MPM programs did not produce:
#  - the fitted model's isotherm (dpd_driver's static crystal) within 1 % of
#    MD's volume per atom at every pressure, held-out ones included;
#  - its C11, C12, C44 at 298 K within 10 % of MD's (as hierarchy_chain),
#    and so its B, C' and E<100>, each recomputed from both sides' Cij;
#  - the front crosses the interface: each slab, DPD and MPM, moves in the
#    order of its distance from the flyer, and the MPM half has a speed;
#  - the run's report.html holds a rendered picture of the impact (the
#    browser test quickstart_report_browser opens it).
# The speeds are printed beside the longitudinal speed sqrt(C11/rho)
# recomputed here from the fitted model's C11 and density.
unset PBMS_SKIP_BUILD  # the command exactly as a user runs it (lib.sh sets it)
start=$(date +%s)
"$PBMS" run "$ROOT/configs/quickstart.yaml" > out.txt 2>&1 || { cat out.txt; fail "quickstart failed"; }
echo "wall time of the quickstart: $(( $(date +%s) - start )) s (MD included, build excluded)"
"$PY" - runs/quickstart <<'PYEOF'
import math, os, sys
import h5py, yaml
from summary_checks import Checks
run = sys.argv[1]
c = Checks()
s = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
c.check(all(st["status"] == "ok" for st in s.values()), "every stage ok")
with h5py.File(f"{run}/results.h5") as f:
    iso = {k: f[f"fit/isotherm/{k}"][:] for k in ("pressure", "volume_per_atom_target", "volume_per_atom", "held_out")}
worst = 0.0
for p, vt, v, h in zip(iso["pressure"], iso["volume_per_atom_target"], iso["volume_per_atom"], iso["held_out"]):
    worst = max(worst, abs(v / vt - 1))
    print(f"     {p / 1e4:5.1f} GPa{' (held out)' if h else '           '}: V_DPD {v:.4f} vs V_MD {vt:.4f} A^3 ({100 * (v / vt - 1):+.3f} %)")
c.check(len(iso["pressure"]) >= 5 and worst <= 0.01,
        f"fitted isotherm within 1 % of MD's at {len(iso['pressure'])} pressures (worst {100 * worst:.3f} %)")
md, dpd = s["elastic_md"]["results"], s["elastic_dpd"]["results"]
for k in ("c11", "c12", "c44"):
    m, d = md[f"{k}_at_t"]["value"], dpd[k]["value"]
    c.check(abs(d / m - 1) <= 0.10, f"{k.upper()} at 298 K: DPD {d:.1f} vs MD {m:.1f} GPa ({100 * (d / m - 1):+.1f} %, tolerance 10 %)")
# The moduli a pull and a compression feel, recomputed here from each
# side's constants: B = (C11 + 2 C12)/3, C' = (C11 - C12)/2 and
# E<100> = 9 B C'/(3 B + C'). Seeds 2026 and 11-13 (2026-12-05): E<100>
# -2.0 to +3.3 %, C' -2.0 to +3.6 %, B -1.6 to -3.4 % of MD's, whose own
# E<100> spans 62.9-71.4 GPa over those seeds (500 atoms).
def moduli(c11, c12):
    b, shear = (c11 + 2 * c12) / 3, (c11 - c12) / 2
    return {"B": b, "C'": shear, "E<100>": 9 * b * shear / (3 * b + shear)}
mm = moduli(md["c11_at_t"]["value"], md["c12_at_t"]["value"])
dm = moduli(dpd["c11"]["value"], dpd["c12"]["value"])
for k in mm:
    c.check(abs(dm[k] / mm[k] - 1) <= 0.10, f"{k} at 298 K: DPD {dm[k]:.2f} vs MD {mm[k]:.2f} GPa ({100 * (dm[k] / mm[k] - 1):+.1f} %, tolerance 10 %)")
imp = {k: v["value"] for k, v in s["impact"]["results"].items()}
order = ["dpd_near", "dpd_far", "mpm_near", "mpm_far"]
arrivals = [imp.get(f"first_motion_{slab}", math.nan) for slab in order]
c.check(all(math.isfinite(t) for t in arrivals) and arrivals == sorted(arrivals),
        "the front crosses the interface: first motion " + ", ".join(f"{n} {t:.2f} ps" for n, t in zip(order, arrivals)))
c.check(imp["dpd_particles"] > 0 and imp["mpm_points"] > 0,
        f"{imp['dpd_particles']:.0f} DPD particles and {imp['mpm_points']:.0f} MPM points")
rho = dpd["density"]["value"]
cl = math.sqrt(dpd["c11"]["value"] * 1e9 / rho)
c.check(math.isfinite(imp.get("wave_speed_far_half", math.nan)), "the MPM half has a wave speed")
print(f"     wave speed: DPD half {imp['wave_speed_near_half']:.0f} m/s, MPM half {imp.get('wave_speed_far_half', math.nan):.0f} m/s;"
      f" sqrt(C11/rho) of the fitted model {cl:.0f} m/s")
body = f"{run}/impact_body.png"
c.check(os.path.getsize(body) > 10000 if os.path.exists(body) else False, f"a rendered picture of the impact: {body}")
page = open(f"{run}/report.html").read() if os.path.exists(f"{run}/report.html") else ""
c.check("impact" in page and page.count("data:image/png;base64,") >= 5, "report.html holds the stages and their pictures inline")
c.exit()
PYEOF
echo "1 passed, 0 failed"
