source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# A concurrent stage gives the same results on 1+1, 2+2 and 1+3 ranks (dpd_driver
# + mpm_driver): every summary value but the timings and the exchanged
# bytes (more ranks, more messages) agrees to 1e-6
# relative (summation order is all that changes); the momentum change, a
# round-off of 1e-16 of M c, stays below 1e-12 on each. The exchange profiles of
# both programs balance: every byte one program's ranks sent, the other's
# received.
CONFIG="$(dirname "$0")/configs/concurrent_small.yaml"
sed 's/launch: {dpd: 1, mpm: 2}/launch: {dpd: 1, mpm: 1}/; s/name: concurrent_small/name: r11/' "$CONFIG" > r11.yaml
sed 's/launch: {dpd: 1, mpm: 2}/launch: {dpd: 2, mpm: 2}/; s/name: concurrent_small/name: r22/' "$CONFIG" > r22.yaml
"$PBMS" run r11.yaml > r11.txt 2>&1 || { cat r11.txt; fail "1+1 run"; }
"$PBMS" run r22.yaml > r22.txt 2>&1 || { cat r22.txt; fail "2+2 run"; }
sed 's/launch: {dpd: 1, mpm: 2}/launch: {dpd: 1, mpm: 3}/; s/name: concurrent_small/name: r13/' "$CONFIG" > r13.yaml
"$PBMS" run r13.yaml > r13.txt 2>&1 || { cat r13.txt; fail "1+3 run"; }
"$PY" - <<'PYEOF'
import math, sys, yaml
a = yaml.safe_load(open("runs/r11/summary.yaml"))["stages"]["impact"]["results"]
bad = 0
for other, label in (("r22", "2+2"), ("r13", "1+3")):
    b = yaml.safe_load(open(f"runs/{other}/summary.yaml"))["stages"]["impact"]["results"]
    for key in set(a) | set(b):
        r = a.get(key, {"value": float("nan")})
        if key not in b:
            bad += 1
            print(f"FAIL {key}: 1+1 only")
            continue
        if key in ("steps_per_second", "nodal_sum_bytes_per_step", "partner_bytes_per_step") or "_exchange_" in key or not isinstance(r, dict) or "value" not in r:
            continue
        x, y = r["value"], b[key]["value"]
        same = (math.isnan(x) and math.isnan(y)) or abs(x - y) <= 1e-6 * max(abs(x), abs(y), 1e-12)
        if key == "momentum_change":  # round-off alone (in units of M c), which the sums' order sets
            same = max(x, y) < 1e-12
        bad += not same
        print(f"{'ok  ' if same else 'FAIL'} {key}: 1+1 {x:.9g}, {label} {y:.9g}")
# The exchange profiles: what one program's ranks sent, the other's received.
import h5py
for run in ("r11", "r22", "r13"):
    with h5py.File(f"runs/{run}/results.h5", "r") as f:
        d, m = f["impact"]["dpd_exchange"], f["impact"]["mpm_exchange"]
        for sender, receiver, kind in ((d, m, "nodal"), (m, d, "nodal"), (m, d, "partner"), (d, m, "partner")):
            sent, got = sender[f"{kind}_bytes_sent"][:].sum(), receiver[f"{kind}_bytes_received"][:].sum()
            same = sent == got and sent > 0
            bad += not same
            print(f"{'ok  ' if same else 'FAIL'} {run} {kind}: {sent:.0f} bytes sent by {sender.name.split('/')[-1]}'s "
                  f"{len(sender['rank'])} ranks, {got:.0f} received by {receiver.name.split('/')[-1]}'s {len(receiver['rank'])}")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
