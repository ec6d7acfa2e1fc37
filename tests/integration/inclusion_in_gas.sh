source "$(dirname "$0")/lib.sh"
# The copper cube in a confining gas (seed §6.2.1, issue 31): the gas of
# configs/inclusion_in_gas.yaml around the cube, at 1 atm (V0) and 5 GPa
# (the whole config, with the argument `all`: also 0.01, 1 and 3 GPa).
# Each holds against references the program did not make:
#  - the seed's counts: 4,631 DPD particles in the cube, 7,930 gas points
#    (21³ - 11³);
#  - the gas pressure reached away from the cube, within 5 % of the target
#    over 10-20 ps (the issue's tolerance; 10-15 ps in the default test's
#    shorter stages);
#  - the cube's V/V0 at 5 GPa (all: 1, 3, 5) within 1 % of the bulk isotherm of the
#    same DPD potential (dpd_isotherm, a periodic crystal with no gas and
#    no grid), its edges measured along the cube's own axes as it turns;
#    seeds 2026-2028 of the whole config (2026-12-08, the surface-fitted
#    Sutton-Chen copper): -0.04 to -0.05 % at 1 GPa and -0.22 to -0.32 %
#    at 5 GPa. With the chapter's Morse model (until 2026-12-08) the faces'
#    relaxation, pressed back by the gas, put 5 GPa at -1.14 to -1.17 %,
#    and only 1 GPa (and 3 GPa in validation) was asserted;
#  - the cube's turn, which a gas of even pressure cannot drive: within 1°
#    of where the stage found it (seeds 2026-2028: -0.54 to +0.70°; 4.9°
#    at 5 GPa when the gas shared the copper's velocity);
#  - the body's mass constant and its momentum, walls' impulse counted,
#    conserved to round-off (1e-12 of M c; measured ~1e-16);
#  - the DPD part at 298 K within 3 % at every pressure, the thermostat's
#    target (seeds 2026-2028 of the whole config: 296.5-297.7 K, 305.7 K
#    for 2028 at 5 GPa). Before 2026-12-07 the gas shared the copper's
#    nodal velocity and heated its surface plane at 5 GPa past what the
#    thermostat takes out (352-377 K): asserted up to 1 GPa only then;
#  - the crystal inside the cube squeezed as the bulk crystal: V/V0 of its
#    interior (the middle 11 of 21 planes along each axis, 665 sites), the
#    determinant of the affine map from their mean sites at 1 atm to each
#    H5MD frame over 10-20 ps, within 1 % of the bulk DPD isotherm at 5 GPa
#    (all: 1, 3, 5; seeds 2026-2028 of the whole config: +0.10 to +0.14,
#    +0.14 to +0.22 and +0.21 to +0.37 %);
#  - fig. 6.4's plot written.
# With the argument `all` (the validation test) the whole config runs, EAM
# copper's MD isotherm included: V/V0 also holds within 1 % of the bulk DPD
# isotherm at 3 GPa and within 1.5 % of MD's at 1, 3 and 5 GPa (seeds
# 2026-2028: -0.17 to -0.20 % and -0.05 to -0.20 %).
CONFIG="$ROOT/configs/inclusion_in_gas.yaml"
ALL=0
[ "${1:-}" = all ] && ALL=1
"$PY" - "$CONFIG" "$ALL" > inclusion.yaml <<'PYEOF'
import sys
import yaml
import derived_config
config = derived_config.load(sys.argv[1])
config["run"] = {"name": "inclusion", "seed": 2026, "output": "runs"}
if sys.argv[2] == "1":
    yaml.safe_dump(config, sys.stdout, sort_keys=False)
    sys.exit(0)
config["launch"] = {"dpd": 1, "mpm": 1}
del config["materials"]["cu_mishin"]
keep = {"dpd_isotherm", "cube", "gas_1atm", "gas_5GPa"}
config["stages"] = [s for s in config["stages"] if s["name"] in keep]
for s in config["stages"]:
    if s["name"] == "dpd_isotherm":
        s["pressures"] = ["0.0001 GPa", "5 GPa"]
    if s["name"] == "cube":
        s["steps"] = 2000
    # 15 ps in the gas, the last 5 sampled (the whole config: 20 ps, the
    # last 10): the surface-fitted model costs twice the Morse model's step.
    if s["name"].startswith("gas_"):
        s["steps"] = 1500
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PYEOF
"$PBMS" run inclusion.yaml > run.out 2>&1 || { tail -30 run.out; fail "the run failed"; }
"$PY" - runs/inclusion "$ALL" <<'PYEOF' || fail "the cube in the gas misses its references"
import sys
import h5py
import numpy as np

run, everything = sys.argv[1], sys.argv[2] == "1"
bad = []
with h5py.File(f"{run}/results.h5", "r") as f:
    def scalar(stage, key):
        return float(f[stage][key][()])
    def bulk(stage, pressure_gpa):
        t = f[stage]["isotherm"]
        p = t["pressure"][:] * (1.0 if stage == "dpd_isotherm" else 1e-4)
        k = int(np.argmin(np.abs(p - pressure_gpa)))
        assert abs(p[k] - pressure_gpa) < 0.05, (stage, p)
        return t["volume_ratio"][k]
    stages = ["gas_1atm", "gas_5GPa"] + (["gas_0.01GPa", "gas_1GPa", "gas_3GPa"] if everything else [])
    for s in stages:
        target = scalar(s, "gas_pressure_target")
        reached = scalar(s, "gas_pressure")
        ratio = scalar(s, "volume_ratio")
        print(f"{s}: {scalar(s, 'dpd_particles'):.0f} DPD, {scalar(s, 'gas_points'):.0f} gas points; "
              f"gas {reached:.5g} GPa of {target:g}; V/V0 {ratio:.5f}; T {scalar(s, 'dpd_temperature'):.1f} K; "
              f"momentum change {scalar(s, 'momentum_change'):.2g}")
        if scalar(s, "dpd_particles") != 4631 or scalar(s, "gas_points") != 7930:
            bad.append(f"{s}: not the seed's 4,631 particles and 7,930 gas points")
        if abs(reached / target - 1.0) > 0.05:
            bad.append(f"{s}: gas at {reached:.4g} GPa, more than 5 % off {target:g}")
        walls = scalar(s, "gas_pressure_on_walls")
        print(f"  the walls' pressure {walls:.5g} GPa ({100 * (walls / target - 1.0):+.2f} %)")
        if target >= 0.5 and abs(walls / target - 1.0) > 0.05:
            bad.append(f"{s}: the walls feel {walls:.4g} GPa, more than 5 % off {target:g}")
        if scalar(s, "momentum_change") > 1e-12:
            bad.append(f"{s}: momentum changed by {scalar(s, 'momentum_change'):.3g} of M c")
        if abs(scalar(s, "dpd_temperature") / 298.0 - 1.0) > 0.03:
            bad.append(f"{s}: the DPD part ends at {scalar(s, 'dpd_temperature'):.1f} K")
        turn = f[s]["body_edges"]["rotation"][:]
        print(f"  the cube turned {turn[-1] - turn[0]:+.2f}° (from {turn[0]:.2f}°)")
        if abs(turn[-1] - turn[0]) > 1.0:
            bad.append(f"{s}: the cube turned by {turn[-1] - turn[0]:+.2f}° in an even gas")
        mass = f[s]["mpm_ledger"]["mass"][:] + f[s]["dpd_ledger"]["mass"][:]
        if np.ptp(mass) > 1e-12 * mass[0]:
            bad.append(f"{s}: the mass changed by {np.ptp(mass):.3g} g/mol")
        if target >= 0.5:
            dpd = bulk("dpd_isotherm", target)
            print(f"  bulk DPD {dpd:.5f} ({100 * (ratio / dpd - 1.0):+.2f} %)")
        if target >= 0.5:
            if abs(ratio / dpd - 1.0) > 0.01:
                bad.append(f"{s}: V/V0 {ratio:.5f} more than 1 % off the bulk DPD {dpd:.5f}")
        if target >= 0.5 and everything:
            md = bulk("md_isotherm", target)
            print(f"  bulk MD {md:.5f} ({100 * (ratio / md - 1.0):+.2f} %)")
            if abs(ratio / md - 1.0) > 0.015:
                bad.append(f"{s}: V/V0 {ratio:.5f} more than 1.5 % off MD's {md:.5f}")
def positions(stage):
    """The cube's particles (sorted by id) in the H5MD frames from 10 ps on."""
    with h5py.File(f"{run}/{stage}/dpd_particles.h5md", "r") as h:
        ids = h["particles/all/id"][:]
        x = h["particles/all/position/value"][:]
        t = h["particles/all/position/time"][:]
    order = np.argsort(ids)
    return ids[order], x[t >= 10.0 - 1e-9][:, order, :]
ids, frames = positions("gas_1atm")
reference = frames.mean(axis=0)
centre = reference.mean(axis=0)
# The interior: sites within 20 Å of the centre along each axis, the middle
# 11 of the 21 planes (5 planes, 18 Å, from every face; a turn of 2° moves
# a site less than the 1.9 Å to the next plane).
inner = np.max(np.abs(reference - centre), axis=1) < 20.0
basis = np.c_[reference[inner] - centre, np.ones(int(inner.sum()))]
with h5py.File(f"{run}/results.h5", "r") as f:
    for s in ("gas_1GPa", "gas_3GPa", "gas_5GPa") if everything else ("gas_5GPa",):
        stage_ids, current = positions(s)
        assert np.array_equal(stage_ids, ids)
        # The interior's deformation from 1 atm: the affine map fitted to its
        # sites in each frame (turn included), its determinant V/V0.
        dets = [np.linalg.det(np.linalg.lstsq(basis, x[inner], rcond=None)[0][:3].T) for x in current]
        interior = float(np.mean(dets))
        dpd = bulk("dpd_isotherm", float(f[s]["gas_pressure_target"][()]))
        print(f"{s}: interior ({int(inner.sum())} sites) V/V0 {interior:.5f}, bulk DPD {dpd:.5f} "
              f"({100 * (interior / dpd - 1):+.2f} %)")
        if abs(interior / dpd - 1.0) > 0.01:
            bad.append(f"{s}: the cube's interior V/V0 {interior:.5f} more than 1 % off the bulk DPD {dpd:.5f}")
import os
if not os.path.isfile(f"{run}/volume_in_gas.png"):
    bad.append("volume_in_gas.png (fig. 6.4) was not written")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
[ "$ALL" = 1 ] && exit 0
# A gas whose sound crosses more than a cell a step (1e-3 g/cm³ at 5 GPa:
# 837 Å/ps against h / dt = 723 Å/ps) stops the job within seconds, the
# message naming a gas point, the part, the stage and the step.
"$PY" - inclusion.yaml > unstable.yaml <<'PYEOF'
import sys
import yaml
config = yaml.safe_load(open(sys.argv[1]))
config["run"]["name"] = "unstable"
stage = next(s for s in config["stages"] if s["name"] == "gas_5GPa")
stage["gas"]["density"] = "0.001 g/cm^3"
stage.pop("volume")
next(s for s in config["stages"] if s["name"] == "cube")["steps"] = 100
config["stages"] = [s for s in config["stages"] if s["name"] in ("cube", "gas_5GPa")]
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PYEOF
rc=0
start=$(date +%s)
timeout 120 "$PBMS" run unstable.yaml > unstable.out 2>&1 || rc=$?
echo "unstable gas: exit code $rc after $(( $(date +%s) - start )) s"
grep "failed" unstable.out | head -2 || true
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || fail "the unstable gas: exit code $rc (124: it hung)"
grep -q "gas point [0-9]" unstable.out || fail "the message does not name the gas point"
grep -q "the gas around the body" unstable.out || fail "the message does not name the gas"
grep -q "stage 'gas_5GPa' at step [0-9]" unstable.out || fail "the message does not name the stage and step"
echo "PASS"
