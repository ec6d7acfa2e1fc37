source "$(dirname "$0")/lib.sh"
# The DPD/MPM-grid model through dpd_run on 1, 2 and 4 ranks
# (configs/dpd_grid_ranks.yaml: a rigid flyer into a thermostatted target,
# 250 grid steps): every scalar of the summary (wave speed, temperature,
# energies, pressure) is the same to the printed precision, and every
# final position agrees with the 1-rank run to 1e-9 Å and every velocity
# to 1e-10 Å/ps (the ranks sum pair forces and nodal contributions in
# another order; a decomposition error moves particles by 1e-4 Å a step).
cfg="$(dirname "$0")/configs/dpd_grid_ranks.yaml"
for n in 1 2 4; do
  "$PBMS" run "$cfg" --ranks dpd=$n --overwrite > out_$n.txt 2>&1 || { cat out_$n.txt; fail "run on $n ranks"; }
  cp runs/dpd_grid_ranks/impact/particles.h5md particles_$n.h5md
  cp runs/dpd_grid_ranks/summary.yaml summary_$n.yaml
  cp runs/dpd_grid_ranks/results.h5 results_$n.h5
done
"$PY" - <<'PYEOF'
import sys, h5py, yaml, numpy as np
stage = {n: yaml.safe_load(open(f"summary_{n}.yaml"))["stages"]["impact"] for n in (1, 2, 4)}
final = {}
for n in (1, 2, 4):
    g = h5py.File(f"particles_{n}.h5md")["particles/all"]
    assert g["position/step"][-1] == 250
    final[n] = g["position/value"][-1], g["velocity/value"][-1]
    edges = np.asarray(g["box/edges/value"][-1])
    edges = np.diag(edges) if edges.ndim == 2 else edges
found = [("wave_speed" in stage[1]["results"], f"1 rank: {stage[1]['results'].get('wave_speed')}")]
for n in (2, 4):
    layout = h5py.File(f"results_{n}.h5")["impact"].attrs["decomposition"]
    layout = layout.decode() if isinstance(layout, bytes) else layout
    found.append((layout != "1x1x1", f"{n} ranks: decomposition {layout}"))
    # Every scalar as the run prints it ({:g}, 6 digits), but the speed.
    for key, result in stage[1]["results"].items():
        if key == "steps_per_second":
            continue
        one, many = f"{result['value']:g}", f"{stage[n]['results'][key]['value']:g}"
        found.append((one == many, f"{n} ranks: {key} {many} (1 rank: {one})"))
    # Periodic y and z: a particle just across a face may be wrapped on
    # one rank count and not yet on another (each wraps when it rebuilds).
    d = final[n][0] - final[1][0]
    d[:, 1:] -= edges[1:] * np.round(d[:, 1:] / edges[1:])
    dx = np.abs(d).max()
    dv = np.abs(final[n][1] - final[1][1]).max()
    found.append((dx < 1e-9 and dv < 1e-10, f"{n} ranks vs 1: max |dx| {dx:.1e} Å (tolerance "
                  f"1e-9), max |dv| {dv:.1e} Å/ps (tolerance 1e-10)"))
for ok, text in found:
    print(f"{'ok  ' if ok else 'FAIL'} {text}")
sys.exit(0 if all(ok for ok, _ in found) else 1)
PYEOF
echo "1 passed, 0 failed"
