source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1
# The (100) surface energy of a Sutton-Chen mesoparticle, the number that
# says how strongly a thin DPD rod feels its surfaces (docs/hierarchy.md,
# "The DPD rod against MD's nanowire"):
#  - dpd_driver's static energies of a slab and a bulk crystal of the fitted
#    model (two dpd_run stages of no step) and its dpd_surface_energy stage
#    give the same surface energy as scripts/sutton_chen_surface.py's
#    lattice sums, to 1e-6 relative (independent sums of one formula);
#  - the script obeys the coarse-graining's scaling: with a -> 2a,
#    epsilon -> 8 epsilon and the cutoff doubled, the cohesive energy per
#    site grows 8 times and the surface energy per area 2 times (each site
#    stands for 8 atoms on 4 times the area), to 1e-9;
#  - the MD reference beside them, Mishin's EAM copper, relaxed by plain
#    lmp: its (100) surface energy within 0.5 % of the 1.345 J/m^2 Mishin
#    et al. (2001) publish, and md_driver's md_surface_energy stage within
#    1e-3 of plain lmp's (the stage relaxes the box to zero pressure first,
#    3.6149 Å where the input file takes 3.615 Å), relaxed and unrelaxed;
#    the same for nickel (CuNi.eam.alloy), whose relaxed box is larger than
#    its input's, so the stage must open the slab where the box ends.
"$PBMS" run "$ROOT/tests/integration/configs/surface_energy_slab.yaml" > run.txt 2>&1 ||
  { cat run.txt; fail "the slab run"; }
lmp -in "$ROOT/tests/integration/eam_surface_100.in" -log none -nocite -screen eam.txt > /dev/null 2>&1 ||
  { tail eam.txt; fail "lmp on eam_surface_100.in"; }
sed -e 's/lattice fcc 3.615/lattice fcc 3.52/' -e 's#Cu_mishin1.eam.alloy Cu#CuNi.eam.alloy Ni#' \
  "$ROOT/tests/integration/eam_surface_100.in" > ni_surface_100.in
grep -q "CuNi.eam.alloy Ni" ni_surface_100.in || fail "the nickel input was not made"
lmp -in ni_surface_100.in -log none -nocite -screen ni.txt > /dev/null 2>&1 || { tail ni.txt; fail "lmp on the nickel input"; }
"$PY" - "$ROOT" <<'PYEOF'
import sys
import yaml
root = sys.argv[1]
sys.path.insert(0, f"{root}/scripts")
from summary_checks import Checks
from sutton_chen_surface import EV_PER_A2_IN_J_PER_M2, SuttonChen, describe
c = Checks()
s = yaml.safe_load(open("runs/surface_energy_slab/summary.yaml"))["stages"]
cfg = yaml.safe_load(open(f"{root}/tests/integration/configs/surface_energy_slab.yaml"))["stages"]
period = [h - l for h, l in zip(cfg[1]["box"]["hi"], cfg[1]["box"]["lo"])][:2]
per_site = s["bulk"]["results"]["potential_energy"]["value"] / s["bulk"]["results"]["particles"]["value"]
slab = s["slab"]["results"]
gamma_engine = (slab["potential_energy"]["value"] - slab["particles"]["value"] * per_site) / (
    2 * period[0] * period[1]) * EV_PER_A2_IN_J_PER_M2
potential = yaml.safe_load(open(f"{root}/configs/potentials/cu_cg_sutton_chen_fitted.yaml"))
model = SuttonChen(potential)
gamma_script = model.surface_energy_100(7.2576) * EV_PER_A2_IN_J_PER_M2
c.check(abs(gamma_engine / gamma_script - 1) < 1e-6,
        f"fitted model: dpd_driver {gamma_engine:.6f} J/m^2, lattice sums {gamma_script:.6f} J/m^2")
stage = s["surface"]["results"]
at_stage = model.surface_energy_100(stage["lattice_constant"]["value"]) * EV_PER_A2_IN_J_PER_M2
c.check(abs(stage["surface_energy_100"]["value"] / at_stage - 1) < 1e-6 and
        abs(stage["lattice_constant"]["value"] / 7.2576 - 1) < 1e-4,
        f"dpd_surface_energy: {stage['surface_energy_100']['value']:.6f} J/m^2 at its zero-pressure "
        f"lattice constant {stage['lattice_constant']['value']:.5f} Å")
c.check(abs(per_site / model.bulk_energy(7.2576) - 1) < 1e-9,
        f"cohesive energy per site: dpd_driver {per_site:.6f} eV, lattice sums {model.bulk_energy(7.2576):.6f} eV")
atomic = {"style": "sutton_chen", "epsilon": 0.012382, "a": 3.61, "n": 9, "m": 6, "c": 39.432, "cutoff": 7.9}
meso = dict(atomic, epsilon=8 * atomic["epsilon"], a=2 * atomic["a"], cutoff=2 * atomic["cutoff"])
one, eight = SuttonChen(atomic), SuttonChen(meso)
lattice = one.lattice_constant(3.61)
e1, e8 = one.bulk_energy(lattice), eight.bulk_energy(2 * lattice)
g1, g8 = one.surface_energy_100(lattice), eight.surface_energy_100(2 * lattice)
c.check(abs(e8 / e1 - 8) < 1e-9 and abs(g8 / g1 - 2) < 1e-9,
        f"scaling: cohesive energy per site {-e1:.4f} -> {-e8:.4f} eV, surface energy "
        f"{g1 * EV_PER_A2_IN_J_PER_M2:.4f} -> {g8 * EV_PER_A2_IN_J_PER_M2:.4f} J/m^2")
eam = {l.split()[1]: float(l.split()[2]) for l in open("eam.txt") if l.startswith("PBMS_SURFACE")}
c.check(abs(eam["relaxed"] / 1.345 - 1) < 0.005,
        f"Mishin EAM copper, plain lmp: (100) surface energy {eam['relaxed']:.4f} J/m^2 relaxed "
        f"({eam['unrelaxed']:.4f} unrelaxed), published 1.345")
ni = {l.split()[1]: float(l.split()[2]) for l in open("ni.txt") if l.startswith("PBMS_SURFACE")}
for stage, ref, metal in (("surface_md", eam, "Cu"), ("surface_md_ni", ni, "Ni")):
    md = s[stage]["results"]
    for key, lmp in (("surface_energy_100", "relaxed"), ("surface_energy_100_unrelaxed", "unrelaxed")):
        c.check(abs(md[key]["value"] / ref[lmp] - 1) < 1e-3 and md[key]["unit"] == "J/m^2",
                f"md_surface_energy {metal} {lmp}: {md[key]['value']:.5f} J/m^2, plain lmp {ref[lmp]:.5f}")
for name in ("cu_cg_sutton_chen", "cu_cg_sutton_chen_fitted"):
    d = describe(yaml.safe_load(open(f"{root}/configs/potentials/{name}.yaml")), 8)
    print(f"info {name}: (100) surface energy {d['surface_energy_100']:.3f} J/m^2, cohesive energy "
          f"{d['cohesive_energy_per_atom']:.3f} eV/atom against EAM copper's {eam['relaxed']:.3f} J/m^2")
c.exit()
PYEOF
echo "1 passed, 0 failed"
