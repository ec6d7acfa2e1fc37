source "$(dirname "$0")/lib.sh"
# The DPD/MPM-grid model tends to DPD-only as the cells shrink (seed §5.2.2):
# the tension rod of configs/dpd_grid_tension.yaml pulled with h = 8, 4 and
# 2 Å and with velocity Verlet, from one equilibrated state per seed, for
# three seeds. The peak-stress difference to DPD-only, averaged over the
# seeds, must shrink at each step 8 -> 4 -> 2 Å by more than twice the
# standard error of that step. Writes convergence.png.
base="$ROOT/configs/dpd_grid_tension.yaml"
for seed in 11 12 13; do
  "$PY" - "$base" "$seed" > "grid_$seed.yaml" <<'PYEOF'
import copy, sys, yaml
import derived_config
cfg = derived_config.load(sys.argv[1])
cfg["run"] = {"name": f"grid_convergence_{sys.argv[2]}", "seed": int(sys.argv[2])}
stages = [s for s in cfg["stages"] if s["name"] in ("equilibrate", "tension_dpd_only")]
grid = next(s for s in cfg["stages"] if s["name"] == "tension")
for h in (8, 4, 2):
    s = copy.deepcopy(grid)
    s["name"] = f"tension_h{h}"
    s["grid"] = {"cell_size": h}
    stages.append(s)
cfg["stages"] = stages
yaml.safe_dump(cfg, sys.stdout, sort_keys=False)
PYEOF
  "$PBMS" run "grid_$seed.yaml" > "run_$seed.txt" 2>&1 || { cat "run_$seed.txt"; fail "seed $seed"; }
done
"$PY" - <<'PYEOF'
import sys, yaml
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
hs = (8, 4, 2)
diff = {h: [] for h in hs}
for seed in (11, 12, 13):
    st = yaml.safe_load(open(f"runs/grid_convergence_{seed}/summary.yaml"))["stages"]
    ref = st["tension_dpd_only"]["results"]["max_stress"]["value"]
    for h in hs:
        diff[h].append(st[f"tension_h{h}"]["results"]["max_stress"]["value"] - ref)
bad = 0
mean = {h: np.mean(diff[h]) for h in hs}
for h in hs:
    print(f"h = {h} A: peak stress minus DPD-only {mean[h]:+.3f} GPa "
          f"(seeds: {', '.join(f'{d:+.3f}' for d in diff[h])})")
for a, b in ((8, 4), (4, 2)):
    step = np.abs(diff[a]).mean() - np.abs(diff[b]).mean()
    # The step's standard error from the per-seed changes of |difference|.
    changes = np.abs(diff[a]) - np.abs(diff[b])
    sigma = changes.std(ddof=1) / np.sqrt(len(changes))
    ok = step > 2 * sigma and step > 0
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} h {a} -> {b} A: |difference| shrinks by {step:.3f} GPa "
          f"(2 sigma = {2 * sigma:.3f} GPa)")
fig, ax = plt.subplots(figsize=(5, 3.5))
for h in hs:
    ax.plot([h] * len(diff[h]), diff[h], "o", color="0.6")
ax.plot(hs, [mean[h] for h in hs], "s-", color="C0", label="mean of 3 seeds")
ax.axhline(0.0, color="k", lw=0.8)
ax.set_xlabel("cell edge h (Å)")
ax.set_ylabel("peak stress − DPD-only (GPa)")
ax.set_title("DPD/MPM-grid tension against DPD-only")
ax.legend()
fig.tight_layout()
fig.savefig("convergence.png", dpi=120)
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
