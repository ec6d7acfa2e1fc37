source "$(dirname "$0")/lib.sh"
# configs/dpd_impact_rod.yaml: the seed's own impact case (§5.2.1), the
# 30 x 10 x 10 a_cg rod with free sides struck by a flyer at 5 Å/ps, on 2
# ranks, timed on the slabs' response: the struck run less the same rod
# from the same start with the same noise and the flyer at rest (the config's
# `rest` stage and impact.baseline). Run seeds 2026, 1 and 2; `short` (the
# default suite's version) runs 2026 alone.
#
# References, recomputed here from the elastic_298K stage's C11, C12 and
# density (the periodic crystal, not the rod):
#  - the response's first motion (0.002 Å) against the dilatational speed
#    sqrt(C11/rho): the leading edge of a pulse in a rod struck over its
#    whole end face is the uniaxial-strain wave until the free sides have
#    had time to release it (one rod width, 72 Å, is of the order of the
#    slabs' distance from the face);
#  - the pulse's body (the mean delay over displacement levels 0.05-0.4 Å)
#    against the thin-bar speed sqrt(E<100>/rho), E<100> = (C11 - C12)
#    (C11 + 2 C12) / (C11 + C12).
# Tolerance 3 % on each: over seeds 2026, 1, 2 and 3 (2026-12-07) the first
# motion read +1.1 to +1.6 % and the pulse +0.5 to +0.8 %, a spread of
# 0.4 points; the rest is the lattice (the dispersion of the discrete
# crystal) and the rod's lateral inertia, which thin-bar theory leaves out.
# The two bands are 27 % apart, so neither speed can pass as the other.
# Also asserted: before the near slab moves, the far slab's response stays
# below 1e-6 Å (measured 4e-10): the baseline cancels the rod's own drift,
# which is 0.2-0.5 Å over the same time.
seeds="2026 1 2"
[ "${1:-}" = short ] && seeds="2026"
mkdir -p potentials && cp "$ROOT"/configs/potentials/cu_cg_morse.yaml potentials/
for seed in $seeds; do
  "$PY" - "$ROOT/configs/dpd_impact_rod.yaml" "$seed" > "rod_$seed.yaml" <<'PYEOF'
import sys, yaml
c = yaml.safe_load(open(sys.argv[1]))
c["run"].update(name=f"dpd_impact_rod_{sys.argv[2]}", seed=int(sys.argv[2]), output="runs")
yaml.safe_dump(c, sys.stdout, sort_keys=False)
PYEOF
  "$PBMS" run "rod_$seed.yaml" > "out_$seed.txt" 2>&1 || { cat "out_$seed.txt"; fail "seed $seed"; }
done
"$PY" - $seeds <<'PYEOF'
import math, sys
from summary_checks import Checks, summary_values

c = Checks()
for seed in sys.argv[1:]:
    value = summary_values(f"dpd_impact_rod_{seed}")
    c11, c12 = value("elastic_298K", "c11"), value("elastic_298K", "c12")
    rho = value("elastic_298K", "density")  # kg/m^3
    e100 = (c11 - c12) * (c11 + 2 * c12) / (c11 + c12)
    lon, bar = (math.sqrt(m * 1e9 / rho) for m in (c11, e100))
    head, pulse = value("impact", "wave_speed"), value("impact", "pulse_speed")
    print(f"     seed {seed}: C11 {c11:.2f}, C12 {c12:.2f}, E<100> {e100:.2f} GPa, rho {rho:.1f} kg/m^3; "
          f"the seed's rod: 3846 m/s")
    c.check(abs(head / lon - 1) <= 0.03,
            f"seed {seed}: the response's first motion {head:.0f} m/s against sqrt(C11/rho) "
            f"{lon:.0f} m/s: {100 * (head / lon - 1):+.2f} % (3 % allowed)")
    c.check(abs(pulse / bar - 1) <= 0.03,
            f"seed {seed}: the pulse {pulse:.0f} m/s against the thin-bar sqrt(E<100>/rho) "
            f"{bar:.0f} m/s: {100 * (pulse / bar - 1):+.2f} % (3 % allowed)")
    residual = value("impact", "baseline_residual")
    c.check(residual < 1e-6,
            f"seed {seed}: the far slab's response before the near slab moves, {residual:.1e} Å < 1e-6 Å")
c.exit()
PYEOF
echo "1 passed, 0 failed"
