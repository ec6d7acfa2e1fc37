source "$(dirname "$0")/lib.sh"
# configs/hierarchy.yaml end to end (validation label; the default suite has
# the shorter checks of each link: md_results_cache, fit_recovery,
# quickstart's fit, mpm_rod_law; calibration_dpd_to_mpm, the hand-off on
# the Morse rod, is validation too). MD isotherm and elastic constants at 298 K ->
# Sutton-Chen fit -> DPD elastic constants and tension -> J2 MPM material ->
# MPM tension. Asserted:
#  - the fitted model's volume per atom within 0.5 % of MD's at every
#    pressure, held-out ones included (issue 18);
#  - its C11, C12, C44 at 298 K (dpd_elastic, 8,000 sampled steps) within
#    10 % of MD's, and C12 - C44 larger than 3 sigma with MD's sign; its B
#    within 4 % of MD's, C' and E<100> within 6 % (a band from four seeds);
#  - the MPM rod's gauge modulus and yield within 5 % of the DPD rod's
#    (issue 18). The MPM material takes the DPD gauge's E and yield, nu and
#    the anisotropy of the DPD crystal; both rods' grips are ramped over
#    5 ps. Unramped, the pull's starting shock made the gauges read a
#    dynamic modulus that depends on the whole stiffness tensor
#    (docs/hierarchy.md);
#  - a second run under a new name whose fit section differs (another
#    optimiser budget) runs no LAMMPS: both MD stages come from the cache.
start=$(date +%s)
"$PBMS" run "$ROOT/configs/hierarchy.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
echo "wall time of hierarchy.yaml: $(( $(date +%s) - start )) s"
sed -e "s|name: hierarchy,|name: hierarchy_refit,|" \
    -e "s|potential_file: potentials/|potential_file: $ROOT/configs/potentials/|" \
    -e "s|local_evaluations: 40, x_tolerance|local_evaluations: 12, x_tolerance|" \
    "$ROOT/configs/hierarchy.yaml" > refit.yaml
grep -q "local_evaluations: 12" refit.yaml || fail "the refit config was not changed"
start=$(date +%s)
"$PBMS" run refit.yaml > refit.txt 2>&1 || { cat refit.txt; fail "refit run"; }
echo "wall time of the refit: $(( $(date +%s) - start )) s"
"$PY" - runs/hierarchy runs/hierarchy_refit <<'PYEOF'
import sys, yaml, h5py
from summary_checks import Checks
run, refit = sys.argv[1], sys.argv[2]
c = Checks()
s = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
with h5py.File(f"{run}/results.h5") as f:
    iso = {k: f[f"fit/isotherm/{k}"][:] for k in ("pressure", "volume_per_atom_target", "volume_per_atom", "held_out")}
worst = 0.0
for p, vt, v, h in zip(iso["pressure"], iso["volume_per_atom_target"], iso["volume_per_atom"], iso["held_out"]):
    r = v / vt - 1
    worst = max(worst, abs(r))
    print(f"     {p / 1e4:5.1f} GPa{' (held out)' if h else '           '}: V_DPD {v:.4f} vs V_MD {vt:.4f} A^3 ({100 * r:+.3f} %)")
c.check(worst <= 0.005, f"volume per atom within 0.5 % of MD at every pressure (worst {100 * worst:.3f} %)")
md, dpd = s["elastic_md"]["results"], s["elastic_dpd"]["results"]
for k in ("c11", "c12", "c44"):
    m, d, e = md[f"{k}_at_t"]["value"], dpd[k]["value"], dpd[f"{k}_error"]["value"]
    c.check(abs(d / m - 1) <= 0.10, f"{k.upper()} at 298 K: DPD {d:.1f} +- {e:.1f} GPa vs MD {m:.1f} GPa ({100 * (d / m - 1):+.1f} %, tolerance 10 %)")
# The moduli tension and compression feel, recomputed from each side's
# constants. The fit weighs B, C' and C44 (since 2026-12-05); seeds 2026-2029
# of this config's first five stages (2026-12-05) gave E<100> -0.7 to +3.1 %,
# C' -0.6 to +3.2 % and B -2.4 to +0.5 % of MD's (MD's own E<100> 59.0-69.7
# GPa). Weighing C11 and C12 instead had left E<100> +15 % (seed 2026).
def moduli(c11, c12):
    b, shear = (c11 + 2 * c12) / 3, (c11 - c12) / 2
    return {"B": b, "C'": shear, "E<100>": 9 * b * shear / (3 * b + shear)}
mm = moduli(md["c11_at_t"]["value"], md["c12_at_t"]["value"])
dmod = moduli(dpd["c11"]["value"], dpd["c12"]["value"])
for k, tol in (("B", 0.04), ("C'", 0.06), ("E<100>", 0.06)):
    c.check(abs(dmod[k] / mm[k] - 1) <= tol, f"{k} at 298 K: DPD {dmod[k]:.2f} vs MD {mm[k]:.2f} GPa ({100 * (dmod[k] / mm[k] - 1):+.1f} %, tolerance {100 * tol:.0f} %)")
dm = md["c12_at_t"]["value"] - md["c44_at_t"]["value"]
dd = dpd["c12"]["value"] - dpd["c44"]["value"]
sig = (dpd["c12_error"]["value"] ** 2 + dpd["c44_error"]["value"] ** 2) ** 0.5
c.check(dd * dm > 0 and abs(dd) > 3 * sig, f"C12 - C44: DPD {dd:.1f} +- {sig:.1f} GPa, MD {dm:.1f} GPa (same sign, > 3 sigma)")
t, m = s["tension"]["results"], s["mpm_tension"]["results"]
a, b = t["gauge_youngs_modulus"]["value"], m["gauge_youngs_modulus"]["value"]
c.check(abs(b / a - 1) <= 0.05, f"gauge E: MPM {b:.2f} vs DPD {a:.2f} GPa ({100 * (b / a - 1):+.1f} %, tolerance 5 %)")
a, b = t["gauge_yield_stress"]["value"], m["gauge_max_stress"]["value"]
c.check(abs(b / a - 1) <= 0.05, f"gauge yield: MPM plateau {b:.2f} vs DPD first load drop {a:.2f} GPa ({100 * (b / a - 1):+.1f} %, tolerance 5 %)")
fit = s["fit"]["results"]
print("     fitted: " + ", ".join(f"{k} {fit[k]['value']:.6g}" for k in ("epsilon", "c", "n", "m") if k in fit)
      + f"; {fit['evaluations']['value']:.0f} candidates, fit wall {s['fit']['wall_s']:.0f} s")
gamma = s["surface_dpd"]["results"]["surface_energy_100"]["value"]
print(f"info the fitted model's (100) surface energy {gamma:.2f} J/m^2 (not a target; EAM copper "
      f"1.345, and seeds 2026-2029 of the fit 2.0-5.1: docs/hierarchy.md)")
log = open(f"{refit}/log.txt").read()
for stage in ("isotherm", "elastic_md"):
    c.check(f"stage '{stage}' reused from the cache" in log, f"refit: {stage} reused from the cache")
# A stage md_driver ran ends with "finished in"; a cached one says where it
# was computed instead.
ran = [st for st in ("isotherm", "elastic_md") if f"stage '{st}' finished in" in log]
c.check(not ran, f"refit: no MD stage ran LAMMPS ({', '.join(ran) or 'none'} did)")
r2 = yaml.safe_load(open(f"{refit}/summary.yaml"))["stages"]
c.check(r2["elastic_md"]["results"]["c11_at_t"]["value"] == md["c11_at_t"]["value"], "refit: the same MD C11 at 298 K")
c.exit()
PYEOF
echo "1 passed, 0 failed"
