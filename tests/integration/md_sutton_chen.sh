source "$(dirname "$0")/lib.sh"
# md_driver's Sutton-Chen material: the setfl table it writes, run by
# LAMMPS' eam/alloy (configs/md_sutton_chen.yaml, md_elastic at 0 K), against
# the Sutton-Chen energy computed here from its formula over the same
# cutoff and switch, E_i = eps [sum_j (a/r)^n S(r)/2 - c sqrt(sum_j (a/r)^m S(r))]:
#  - the relaxed lattice parameter, where dE/da = 0, within 1e-5 relative
#    (the table's interpolation; LAMMPS' relaxation stops at 1e-10 force);
#  - C11, C12 and C44, second derivatives of the energy per volume, within
#    0.2 % (md_elastic's +/-0.1 % strains differ from the second
#    derivative by O(1e-3) relative for copper's third-order constants).
"$PBMS" run "$ROOT/tests/integration/configs/md_sutton_chen.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
[ -s runs/md_sutton_chen/elastic/cu_sc.sutton_chen.eam.alloy ] || fail "no table written"
"$PY" - runs/md_sutton_chen <<'PYEOF'
import sys, math, yaml
import numpy as np
from summary_checks import Checks
c = Checks()
r = yaml.safe_load(open(f"{sys.argv[1]}/summary.yaml"))["stages"]["elastic"]["results"]
eps, a, cc, n, m, cut, smooth = 0.012382, 3.61, 39.432, 9, 6, 7.9, 0.5
def switch(d):
    x = np.clip((d - (cut - smooth)) / smooth, 0.0, 1.0)
    return np.where(d < cut, 1 - x**3 * (10 - 15 * x + 6 * x * x), 0.0)
cells = np.array([[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]])
k = np.arange(-4, 5)
grid = np.array(np.meshgrid(k, k, k, indexing="ij")).reshape(3, -1).T
sites = (grid[:, None, :] + cells[None, :, :]).reshape(-1, 3)
sites = sites[np.any(sites != 0, axis=1)]
def energy(a0, strain=np.zeros((3, 3))):
    # Energy per atom of the fcc crystal of lattice parameter a0 under the
    # deformation I + strain.
    d = np.linalg.norm(sites @ (a0 * (np.eye(3) + strain)).T, axis=1)
    d = d[d < cut]
    s = switch(d)
    return eps * (0.5 * np.sum((a / d)**n * s) - cc * math.sqrt(np.sum((a / d)**m * s)))
lo, hi = 3.4, 3.8  # golden-section search for dE/da = 0
g = (math.sqrt(5) - 1) / 2
for _ in range(200):
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    lo, hi = (lo, x2) if energy(x1) < energy(x2) else (x1, hi)
a0 = (lo + hi) / 2
vol = a0**3 / 4
h = 1e-4
def e(**kw):
    s = np.zeros((3, 3))
    for key, v in kw.items():
        i, j = int(key[1]) - 1, int(key[2]) - 1
        s[i, j] += v
        if i != j:
            s[j, i] += v
    return energy(a0, s)
to_gpa = 160.21766208
e0 = energy(a0)
c11 = (e(e11=h) - 2 * e0 + e(e11=-h)) / h**2 / vol * to_gpa
c12 = (e(e11=h, e22=h) - e(e11=h, e22=-h) - e(e11=-h, e22=h) + e(e11=-h, e22=-h)) / (4 * h * h) / vol * to_gpa
c44 = (e(e23=h / 2) - 2 * e0 + e(e23=-h / 2)) / h**2 / vol * to_gpa
got = r["lattice_parameter"]["value"]
c.check(abs(got / a0 - 1) < 1e-5, f"lattice parameter {got:.6f} A against {a0:.6f} A from the formula ({got / a0 - 1:+.1e})")
for name, want in (("c11", c11), ("c12", c12), ("c44", c44)):
    v = r[name]["value"]
    c.check(abs(v / want - 1) < 2e-3, f"{name.upper()} {v:.3f} GPa against {want:.3f} GPa from the formula ({100 * (v / want - 1):+.3f} %)")
print(f"     cohesive energy from the formula: {-e0:.4f} eV per atom")
c.exit()
PYEOF
