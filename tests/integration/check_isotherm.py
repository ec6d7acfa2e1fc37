"""Physics and bookkeeping checks on a finished md_isotherm run of EAM Cu at 298 K.

Agreement with the program's own numbers proves nothing, so this script
holds none. The run is compared with
  - plain `lmp` on the same inputs: md_isotherm_vs_lmp.sh (to 1e-9);
  - physical references, here, each with the tolerance it can support:
    the Mishin (2001) potential's own 0 K lattice parameter and bulk
    modulus, and experiment on copper at room temperature.
"""
import sys
import h5py
import numpy as np
import yaml

run = sys.argv[1]
summary = yaml.safe_load(open(f"{run}/summary.yaml"))
manifest = yaml.safe_load(open(f"{run}/manifest.yaml"))
stage = summary["stages"]["isotherm"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


check(stage["status"] == "ok", "stage status ok")
check(manifest["status"] == "ok", "manifest status ok")
check(manifest["git_hash"] != "", "manifest records the git hash")
check("lammps" in manifest["software"], "manifest records the LAMMPS version")
res = stage["results"]
a = res["lattice_parameter"]["value"]
B = res["bulk_modulus"]["value"]
check(res["bulk_modulus"]["unit"] == "GPa", "bulk modulus unit is GPa")

# Lattice parameter. The potential puts the static fcc minimum at 3.615 Å
# (md_elastic_0K checks that to 1e-3 Å), which is also copper's measured
# lattice parameter at 298 K. Classical MD has no zero-point motion and no
# quantum suppression of the expansion at low T, so from 0 to 298 K it
# expands by about alpha(298 K) x 298 K = 16.5e-6/K x 298 K = 0.49 %, where
# copper itself expands by 0.32 % (Touloukian). Accept a thermal strain of
# 0.25 to 0.75 % over the potential's 0 K value, i.e. +-50 % of the classical
# estimate for the potential's anharmonicity: that catches a missing
# thermostat (0 %), twice the temperature (~1 %) or a wrong lattice (>1 %).
# Against experiment the same window reads: 0.25-0.75 % above 3.615 Å.
a_static = 3.615
strain = a / a_static - 1
check(0.0025 < strain < 0.0075,
      f"lattice parameter {a:.5f} Å: thermal strain {100 * strain:.3f} % over the potential's "
      f"0 K value {a_static} Å, in [0.25, 0.75] % (classical estimate 0.49 %); "
      f"{100 * strain:+.2f} % against experiment at 298 K (3.615 Å)")

# Bulk modulus. Experiment at room temperature, isothermal: B_T = 133 GPa,
# B' = 5.3 (Dewaele, Loubeyre & Mezouar, PRB 70, 094112 (2004)). The potential
# gives 138.4 GPa at 0 K (from its C11 and C12), 2.5 % below copper's 0 K
# value of 142 GPa; from 0 to 298 K copper softens by ~3.5 % and the
# isothermal modulus lies ~3 % below the adiabatic one. Accept 8 % around
# 133 GPa: twice the potential's own 0 K misfit plus the statistical error of
# a five-point fit of 10 ps averages (~1 %).
check(abs(B - 133.0) / 133.0 < 0.08,
      f"bulk modulus {B:.2f} GPa within 8 % of copper's isothermal 133 GPa at 298 K "
      f"(the potential: 138.4 GPa at 0 K)")

with h5py.File(f"{run}/results.h5", "r") as f:
    g = f["isotherm/isotherm"]
    p = g["pressure_target"][:]
    ratio = g["volume_ratio"][:]
    check(g["pressure"].attrs["unit"] in ("bar", b"bar"), "pressure column has unit bar")
    check(f["isotherm/bulk_modulus"].attrs["unit"] in ("GPa", b"GPa"), "scalar has a unit")
    i5 = int(np.argmin(abs(p - 5e4)))
    check(abs(p[i5] - 5e4) < 1, "a 5 GPa point exists")
    # Compression at 5 GPa: 1 - V/V0 = 0.0338 on the experimental isotherm
    # (Vinet form, B_T = 133 GPa, B' = 5.3). To first order it is P / B, so
    # the tolerance of 10 % of it (V/V0 within +-0.34 %) follows the bulk
    # modulus's: it allows the potential's few-% misfit and catches a pressure
    # off by a factor or in the wrong unit.
    compression_exp = 1 - 0.96624
    compression = 1 - ratio[i5]
    check(abs(compression - compression_exp) / compression_exp < 0.10,
          f"V/V0 at 5 GPa = {ratio[i5]:.5f}: compression {compression:.4f} within 10 % of "
          f"experiment's {compression_exp:.4f} (V/V0 = 0.96624)")
    check(np.all(np.diff(ratio) < 0), "volume falls with pressure")

sys.exit(1 if failures else 0)
