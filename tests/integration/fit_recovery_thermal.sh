source "$(dirname "$0")/lib.sh"
# fit_dpd_potential recovers potentials at 298 K from targets the DPD engine
# computed with them at 298 K and the run's seed (isotherm and C11, C12,
# C44), each started 10-20 % away: Morse (d0, alpha, r0) and Sutton-Chen
# (epsilon, c, n, m). A static pre-fit, then the thermal polish. Every free
# parameter must end within max(1 %, 3 sigma) of the truth, sigma being the
# std_error the fit reports from the judge's block errors (issue 18), and the
# objective must fall to a millionth of the start's. The short version in the
# default suite is fit_recovery (the same fits on the static crystal). The
# targets and the judge share the run's seed here, so the fits end far
# inside sigma; fit_judge_seed_spread checks sigma against the spread of fits
# judged at other seeds.
cfg="$ROOT/tests/integration/configs"
for form in morse sutton_chen; do
  "$PBMS" run "$cfg/fit_recovery_thermal_$form.yaml" > "$form.txt" 2>&1 ||
    { cat "$form.txt"; fail "$form fit"; }
done
"$PY" - "$cfg" <<'PYEOF'
import sys, yaml, h5py
from checklist import Checklist

cfg = sys.argv[1]
check = Checklist()
for form, free in (("morse", ("d0", "alpha", "r0")),
                   ("sutton_chen", ("epsilon", "c", "n", "m"))):
    run = f"fit_recovery_thermal_{form}"
    materials = yaml.safe_load(open(f"{cfg}/{run}.yaml"))["materials"]
    truth, start = materials["truth"]["potential"], materials["start"]["potential"]
    stages = yaml.safe_load(open(f"runs/{run}/summary.yaml"))["stages"]
    static, fit = stages["fit_static"]["results"], stages["fit"]["results"]
    h5 = h5py.File(f"runs/{run}/results.h5")
    log = h5["fit/evaluation_log"]
    check(set(log["temperature"][:]) == {298.0}, f"{run}: every thermal candidate judged at 298 K")
    for k in free:
        t = truth[k]
        away = abs(start[k] - t) / abs(t)
        check(0.1 <= away <= 0.2, f"{run}: {k} starts {away:.1%} away from the truth {t}")
        sigma = fit[k].get("std_error", float("nan"))
        check(sigma > 0, f"{run}: {k} has a standard error ({sigma:.3g})")
        tolerance = max(0.01 * abs(t), 3 * sigma)
        err = abs(fit[k]["value"] - t)
        pre = abs(static[k]["value"] - t)
        check(err <= tolerance,
              f"{run}: {k} = {fit[k]['value']:.8g}, error {err:.2e} ({err / abs(t):.1e} relative, "
              f"{err / sigma:.1e} sigma) within max(1 % = {0.01 * abs(t):.3g}, 3 sigma = "
              f"{3 * sigma:.3g}); the static pre-fit was {pre / abs(t):.2%} and {pre / sigma:.1f} sigma off")
    # The start's objective: the static pre-fit's first candidate is the start.
    first = h5["fit_static/evaluation_log"]
    check(all(first[k][0] == start[k] for k in free), f"{run}: the first candidate is the start")
    begin, polish, end = first["objective"][0], log["objective"][0], fit["objective"]["value"]
    # Near the truth the residuals are linear in the parameters' errors, so
    # a millionth of the objective is a thousandth of the start's residuals.
    check(end <= 1e-6 * begin,
          f"{run}: objective {end:.2e} at the end, {begin:.3g} at the start (ratio {end / begin:.1e}, "
          f"at most 1e-6); the thermal polish started at {polish:.2e}")
sys.exit(check.finish())
PYEOF
