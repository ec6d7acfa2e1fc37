source "$(dirname "$0")/lib.sh"
# configs/hierarchy.yaml end to end (validation label; the default suite has
# the shorter checks of each link: md_results_cache, fit_recovery,
# quickstart's fit, mpm_rod_law; calibration_dpd_to_mpm, the hand-off on
# the Morse rod, is validation too). MD isotherm and elastic constants at 298 K ->
# Sutton-Chen fit -> DPD elastic constants and tension -> J2 MPM material ->
# MPM tension. Asserted:
#  - the fitted model's volume per atom within 0.5 % of MD's at every
#    pressure, held-out ones included (issue 18);
#  - its moduli at 298 K (dpd_elastic, 8,000 sampled steps) against MD's:
#    B, C' and C44 within 5 %, E<100> within 3 % (check_fit_against_md.py),
#    and C12 - C44 larger than 3 sigma with MD's sign;
#  - the fit's judged surface energy is surface_dpd's (reported beside
#    MD's, not trained);
#  - the MPM rod's gauge modulus and yield within 5 % of the DPD rod's
#    (issue 18). The MPM material takes the DPD gauge's E and yield, nu and
#    the anisotropy of the DPD crystal; both rods' grips are ramped over
#    5 ps. Unramped, the pull's starting shock made the gauges read a
#    dynamic modulus that depends on the whole stiffness tensor
#    (docs/hierarchy.md);
#  - a second run under a new name whose fit section differs (another
#    optimiser budget) runs no LAMMPS: the three MD stages come from the cache.
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
import sys, yaml
from summary_checks import Checks
from check_fit_against_md import check_fit
run, refit = sys.argv[1], sys.argv[2]
c = Checks()
# The fitted crystal against MD (issue 32, "The fit"): volumes 0.5 %, B,
# C' and C44 5 %, E<100> 3 % (check_fit_against_md.py; nickel's chain,
# fit_second_metal, is held to the same). Until 2026-12-06 this test held
# C11, C12, C44 to 10 %, B to 4 % and C' and E<100> to 6 %, a band from four
# seeds whose MD targets themselves spread by 8 % in E<100> (20 ps, +-0.5 %
# strains; now 40 ps, +-1 %: docs/hierarchy.md).
s = check_fit(c, run)
md, dpd = s["elastic_md"]["results"], s["elastic_dpd"]["results"]
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
gamma_md = s["surface_md"]["results"]["surface_energy_100"]["value"]
c.check(abs(fit["surface_energy_100"]["value"] / gamma - 1) < 1e-9,
        f"the fit's judged surface energy {fit['surface_energy_100']['value']:.4f} J/m^2 is surface_dpd's")
print(f"info the fitted model's (100) surface energy {gamma:.2f} J/m^2 against MD's {gamma_md:.3f} "
      f"(reported, weight 0: docs/hierarchy.md, \"A surface target\")")
log = open(f"{refit}/log.txt").read()
for stage in ("isotherm", "elastic_md", "surface_md"):
    c.check(f"stage '{stage}' reused from the cache" in log, f"refit: {stage} reused from the cache")
# A stage md_driver ran ends with "finished in"; a cached one says where it
# was computed instead.
ran = [st for st in ("isotherm", "elastic_md", "surface_md") if f"stage '{st}' finished in" in log]
c.check(not ran, f"refit: no MD stage ran LAMMPS ({', '.join(ran) or 'none'} did)")
r2 = yaml.safe_load(open(f"{refit}/summary.yaml"))["stages"]
c.check(r2["elastic_md"]["results"]["c11_at_t"]["value"] == md["c11_at_t"]["value"], "refit: the same MD C11 at 298 K")
c.exit()
PYEOF
echo "1 passed, 0 failed"
