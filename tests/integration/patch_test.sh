source "$(dirname "$0")/lib.sh"
# The interface's patch test (issue 32). Every lattice plane of a body's MPM
# part (its mean displacement along the interface's normal, every 10 steps)
# may move no more than the same plane in the same body all DPD, plus
# 0.05 Å (the issue's bound), over 2 ps with the momentum-conserving
# interface and the ghost-force correction; without the correction the
# first MPM planes are pushed by DPD neighbours whose MPM counterparts the
# continuum lacks, and some plane moves more than 0.1 Å. Each check prints
# the worst plane and its depth from the nearer interface.
# - configs/patch_test.yaml, 0 K: a periodic block with a slab of MPM points
#   across x, y and z in turn, at rest and under a uniform strain of 1 %
#   along every axis (the dead loads measured at rest, the MPM points
#   starting with the strained crystal's stress). All DPD, no plane moves.
# - configs/patch_test_298K.yaml, 298 K: the 24 x 6 x 6 a_cg rod with its
#   middle third MPM and its ends gripped, three equilibrated rods, the dead
#   loads measured on each at rest over 6 ps first.
"$PBMS" run "$(dirname "$0")/configs/patch_test.yaml" > run.txt 2>&1 || { cat run.txt; fail "patch test run (0 K)"; }
"$PBMS" run "$(dirname "$0")/configs/patch_test_298K.yaml" > run_298K.txt 2>&1 || { cat run_298K.txt; fail "patch test run (298 K)"; }
"$PY" - <<'PYEOF'
import h5py
import numpy as np
from summary_checks import Checks

checks = Checks()
BOUND = 0.05  # Å, the issue's


class Run:
    def __init__(self, name, faces):
        self.results = h5py.File(f"runs/{name}/results.h5", "r")
        self.faces = faces  # the MPM region's faces along the normal, Å (the config's)

    def profiles(self, stage, side):
        """Plane centres and each plane's displacement at every profile, Å."""
        g = self.results[stage][f"{side}_profiles"]
        keys = sorted((k for k in g if k.startswith("t=")), key=lambda k: float(k[2:]))
        return g["position"][()], np.array([g[k][()] for k in keys])

    def worst_plane(self, stage, reference):
        """The MPM plane moving most beyond the same plane all DPD."""
        centre, mpm = self.profiles(stage, "mpm")
        _, dpd = self.profiles(reference, "dpd")
        held = ~np.all(np.isnan(mpm), axis=0)
        most = np.nanmax(np.abs(mpm[:, held]), axis=0)
        excess = most - np.nanmax(np.abs(dpd[:, held]), axis=0)
        k = int(np.argmax(excess))
        depth = min(abs(centre[held][k] - f) for f in self.faces)
        return excess[k], depth, int(held.sum())

    def judge(self, what, corrected, uncorrected, reference):
        excess, depth, planes = self.worst_plane(corrected, reference)
        checks.check(excess <= BOUND,
                     f"{what}, corrected: the worst of {planes} MPM planes moves {excess:+.3f} Å "
                     f"beyond all DPD (bound {BOUND} Å), {depth:.2f} Å from the interface")
        excess, depth, planes = self.worst_plane(uncorrected, reference)
        checks.check(excess > 0.1,
                     f"{what}, uncorrected: the ghost forces move the worst plane {excess:.3f} Å "
                     f"beyond all DPD, {depth:.2f} Å from the interface (above 0.1 Å)")


cold = Run("patch_test", (57.84, 119.295))
for axis in "xyz":
    _, dpd = cold.profiles(f"{axis}_all_dpd", "dpd")
    print(f"info 0 K, {axis}_all_dpd: the lattice's planes move {np.nanmax(np.abs(dpd)):.1e} Å")
    cold.judge(f"0 K, slab across {axis}, at rest", f"{axis}_corrected", f"{axis}_uncorrected",
               f"{axis}_all_dpd")
    cold.judge(f"0 K, slab across {axis}, 1 % strained", f"{axis}_strained_corrected",
               f"{axis}_strained_uncorrected", f"{axis}_strained_all_dpd")
warm = Run("patch_test_298K", (56.0325, 117.4875))
for n in (1, 2, 3):
    _, dpd = warm.profiles(f"all_dpd_{n}", "dpd")
    print(f"info 298 K, rod {n} all DPD: its planes move up to {np.nanmax(np.abs(dpd)):.3f} Å")
    warm.judge(f"298 K, rod {n} at rest", f"corrected_{n}", f"uncorrected_{n}", f"all_dpd_{n}")
checks.exit()
PYEOF
