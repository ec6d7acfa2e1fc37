source "$(dirname "$0")/lib.sh"
# The DPD/MPM-grid model through dpd_run on 1, 2 and 4 ranks
# (configs/dpd_grid_ranks.yaml: a rigid flyer into a thermostatted target,
# 250 grid steps), with each of the two moves (grid.move).
# - step_start: every scalar of the summary (wave speed, temperature,
#   energies, pressure) is the same to the printed precision, and every
#   final position agrees with the 1-rank run to 1e-9 Å and every velocity
#   to 1e-10 Å/ps (the ranks sum pair forces and nodal contributions in
#   another order; a decomposition error moves particles by 1e-4 Å a step).
# - midpoint (the default): a particle whose midpoint stands past its
#   rank's box takes its weights at the box's face (MpmSolver), the one
#   change beyond round-off: every position within 1e-4 Å of the 1-rank
#   run's and every velocity within 1e-2 Å/ps after 250 steps (measured
#   1.1e-5 Å and 3.5e-4 Å/ps on 4 ranks), the scalars to 4 digits.
src="$(dirname "$0")/configs/dpd_grid_ranks.yaml"
for move in step_start midpoint; do
  sed "s/grid: {cell_size: 3.615}/grid: {cell_size: 3.615, move: $move}/" "$src" > dpd_grid_ranks.yaml
  grep -q "move: $move" dpd_grid_ranks.yaml || fail "the config's grid line changed"
  for n in 1 2 4; do
    "$PBMS" run dpd_grid_ranks.yaml --ranks dpd=$n --overwrite > out_$n.txt 2>&1 || { cat out_$n.txt; fail "run on $n ranks"; }
    cp runs/dpd_grid_ranks/impact/particles.h5md particles_$n.h5md
    cp runs/dpd_grid_ranks/summary.yaml summary_$n.yaml
    cp runs/dpd_grid_ranks/results.h5 results_$n.h5
  done
  MOVE=$move "$PY" - <<'PYEOF' || fail "$move: ranks disagree"
import os
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
    exact = os.environ["MOVE"] == "step_start"
    for key, result in stage[1]["results"].items():
        if key == "steps_per_second":
            continue
        fmt = "{:g}" if exact else "{:.4g}"
        one, many = fmt.format(result["value"]), fmt.format(stage[n]["results"][key]["value"])
        found.append((one == many, f"{n} ranks: {key} {many} (1 rank: {one})"))
    # Periodic y and z: a particle just across a face may be wrapped on
    # one rank count and not yet on another (each wraps when it rebuilds).
    d = final[n][0] - final[1][0]
    d[:, 1:] -= edges[1:] * np.round(d[:, 1:] / edges[1:])
    dx = np.abs(d).max()
    dv = np.abs(final[n][1] - final[1][1]).max()
    tx, tv = (1e-9, 1e-10) if exact else (1e-4, 1e-2)
    found.append((dx < tx and dv < tv, f"{n} ranks vs 1: max |dx| {dx:.1e} Å (tolerance "
                  f"{tx:g}), max |dv| {dv:.1e} Å/ps (tolerance {tv:g})"))
for ok, text in found:
    print(f"{'ok  ' if ok else 'FAIL'} {os.environ['MOVE']}: {text}")
sys.exit(0 if all(ok for ok, _ in found) else 1)
PYEOF
done
echo "1 passed, 0 failed"
