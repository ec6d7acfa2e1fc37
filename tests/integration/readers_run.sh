source "$(dirname "$0")/lib.sh"
# The run whose files readers_mdanalysis.py, readers_export.py and
# readers_paraview.py open: md, dpd and mpm stages (configs/readers.yaml).
# A rerun of this test replaces the run it made before, on purpose.
rm -rf runs/readers
"$PBMS" run "$ROOT/tests/integration/configs/readers.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
for f in md/p0.h5md dpd/particles.h5md mpm_consistent/particles.h5md mpm_metal/particles.h5md \
         md_tension/tension.h5md concurrent/dpd_particles.h5md concurrent/mpm_particles.h5md \
         mpm_consistent/grid.xdmf mpm_metal/grid.xdmf; do
  [ -f "runs/readers/$f" ] || fail "no runs/readers/$f"
done
echo "1 passed, 0 failed"
