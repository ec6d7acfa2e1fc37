source "$(dirname "$0")/lib.sh"
# configs/dpd_impact.yaml (seed §5.2.1, laterally periodic target) on 2
# ranks: the wave speed, timed half way up the two slabs' velocity rise,
# against the speed predicted from the model itself and the slabs' measured
# particle velocity u_p (mean of the two slabs' velocity at the top of the
# front): the leading-front speed of the Rayleigh lines of the model's
# uniaxial-strain stress at 298 K (stage uniaxial_298K; the state behind a
# plane front in a target with its sides held; the hydrostatic isotherm
# P(V) would miss the deviatoric stress, C11 against K, 16 % in speed).
#
# Tolerance 3 %: over seeds 1, 2, 3 and 2026 the measured speed scatters by
# ±0.5 % (4570-4614 m/s, -1.1 to -0.1 % from the prediction), and the
# prediction rests on the isothermal, thermally smeared sigma_xx(eps):
# steady pistons at u_p = 67-128 m/s (exploratory runs) measured 1.5-2.8 %
# above it, and the static curve lies 1.1 % above the 298 K one at
# eps = 0.02 (docs/dpd-driver.md). The single shock to u_p would be 7 % off.
# The old bracket [0.95 bar, 1.05 longitudinal] and the first-motion speed
# are printed for information.
"$PBMS" run "$ROOT/configs/dpd_impact.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
"$PY" - <<'PYEOF'
from impact_prediction import predicted_front_speed, rayleigh_table
from summary_checks import Checks, summary_values

value = summary_values("dpd_impact")
c = Checks()
v = value("impact", "wave_speed")
u_p = value("impact", "particle_velocity")
table = rayleigh_table("runs/dpd_impact/results.h5", "uniaxial_298K")
predicted, single = predicted_front_speed(table, u_p)
bar = value("elastic_298K", "bar_speed")
lon = value("elastic_298K", "longitudinal_speed")
print(f"     u_p = {u_p:.1f} m/s (front velocity near {value('impact', 'front_velocity_near'):.1f}, "
      f"far {value('impact', 'front_velocity_far'):.1f} m/s)")
print(f"     single-shock U_s(u_p) = {single:.0f} m/s; sqrt(C11/rho) = {lon:.0f} m/s; "
      f"first-motion speed {value('impact', 'first_motion_speed'):.0f} m/s (seed's rod: 3846)")
c.check(abs(v - predicted) / predicted <= 0.03,
        f"wave speed {v:.0f} m/s against the predicted leading front {predicted:.0f} m/s: "
        f"{100 * (v - predicted) / predicted:+.2f} % (3 % allowed)")
# 3 % alone would also pass sqrt(C11/rho), 1.6 % below the prediction
# here: the measured speed must also lie nearer the prediction than both
# the single shock to u_p and the small-amplitude sound speed.
c.check(abs(v - predicted) < min(abs(v - single), abs(v - lon)),
        f"nearer the prediction ({abs(v - predicted):.0f} m/s) than the single shock "
        f"({abs(v - single):.0f}) or sqrt(C11/rho) ({abs(v - lon):.0f} m/s)")
print(f"info wave speed {v:.0f} m/s in [0.95 x {bar:.0f}, 1.05 x {lon:.0f}] m/s: "
      f"{0.95 * bar <= v <= 1.05 * lon}")
c.exit()
PYEOF
echo "1 passed, 0 failed"
