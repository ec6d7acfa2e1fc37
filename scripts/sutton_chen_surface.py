#!/usr/bin/python3
"""Static lattice sums of a Sutton-Chen fcc crystal: the lattice constant,
the cohesive energy per site and the unrelaxed (100) surface energy.

Usage: /usr/bin/python3 scripts/sutton_chen_surface.py POTENTIAL.yaml [...]
       /usr/bin/python3 scripts/sutton_chen_surface.py --atoms-per-site 8 POTENTIAL.yaml

POTENTIAL.yaml is a `sutton_chen` potential as configs/potentials/ holds
them (epsilon eV, a Å, n, m, c, cutoff Å, optional p). The energy of site i
is epsilon [ 1/2 sum_j (a/r_ij)^n - c F(rho_i) ], rho_i = sum_j (a/r_ij)^m,
with a sharp cutoff, as dpd_driver's kernel computes it: F = rho^p, plus
flattening rho_c^p (knee - rho/rho_c)^3 below the knee (rho_c: a site's
density in the perfect crystal of lattice constant a). The surface energy is that of a
slab of 12 (100) planes, periodic across, against as many bulk sites, over
both faces; no relaxation (for Mishin's EAM copper relaxing the (100)
surface lowers it by 0.4 %: 1.351 to 1.345 J/m^2, plain lmp).

Why a script and not a stage: this is the number that says how strongly a
thin rod of the model feels its surfaces (docs/hierarchy.md, "The DPD rod
against MD's nanowire"); the fit does not target it yet.
"""

import argparse
import sys

import numpy as np
import yaml
from scipy.optimize import minimize_scalar

EV_PER_A2_IN_J_PER_M2 = 16.021766
FCC_BASIS = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])


def fcc_sites(nx, ny, nz):
    cells = np.array([[i, j, k] for i in range(nx) for j in range(ny) for k in range(nz)])
    return (cells[:, None, :] + FCC_BASIS[None]).reshape(-1, 3)


class SuttonChen:
    def __init__(self, p):
        self.eps, self.a, self.n, self.m = p["epsilon"], p["a"], p["n"], p["m"]
        self.c, self.cutoff, self.p = p["c"], p["cutoff"], p.get("p", 0.5)
        self.knee, self.flattening = p.get("knee", 1.0), p.get("flattening", 0.0)
        self.rho_c = self.crystal_density()

    def crystal_density(self):
        reach = int(np.ceil(self.cutoff / self.a)) + 1
        r = np.linalg.norm(fcc_sites(2 * reach + 1, 2 * reach + 1, 2 * reach + 1) - reach, axis=1)
        r = r[(r > 1e-9) & (r * self.a < self.cutoff)] * self.a
        return np.sum((self.a / r)**self.m)

    def embedding(self, rho):
        below = max(self.knee - rho / self.rho_c, 0.0)
        return rho**self.p + self.flattening * self.rho_c**self.p * below**3

    def site_energies(self, pos, period, sites):
        """Energies of `sites`, with images of `pos` along the axes whose
        period is finite."""
        reach = [int(np.ceil(self.cutoff / L)) if np.isfinite(L) else 0 for L in period]
        shifts = np.array([[i * period[0] if reach[0] else 0, j * period[1] if reach[1] else 0,
                            k * period[2] if reach[2] else 0]
                           for i in range(-reach[0], reach[0] + 1)
                           for j in range(-reach[1], reach[1] + 1)
                           for k in range(-reach[2], reach[2] + 1)])
        images = (pos[None, :, :] + shifts[:, None, :]).reshape(-1, 3)
        out = []
        for i in sites:
            r = np.linalg.norm(images - pos[i], axis=1)
            r = r[(r > 1e-9) & (r < self.cutoff)]
            x = self.a / r
            out.append(self.eps * (0.5 * np.sum(x**self.n) - self.c * self.embedding(np.sum(x**self.m))))
        return np.array(out)

    def bulk_energy(self, lattice):
        cells = int(np.ceil(2 * self.cutoff / lattice)) + 1
        pos = fcc_sites(cells, cells, cells) * lattice
        return self.site_energies(pos, [cells * lattice] * 3, [0])[0]

    def lattice_constant(self, guess):
        return minimize_scalar(self.bulk_energy, bracket=(0.97 * guess, guess, 1.03 * guess)).x

    def surface_energy_100(self, lattice, planes=12):
        """(E_slab - N E_bulk) / 2A in eV/Å^2."""
        across = int(np.ceil(2 * self.cutoff / lattice)) + 1
        pos = fcc_sites(across, across, (planes + 1) // 2) * lattice
        pos = pos[pos[:, 2] < planes * lattice / 2 - 1e-6]
        period = [across * lattice, across * lattice, np.inf]
        energy = self.site_energies(pos, period, range(len(pos))).sum()
        return (energy - len(pos) * self.bulk_energy(lattice)) / (2 * period[0] * period[1])


def describe(potential, atoms_per_site):
    model = SuttonChen(potential)
    lattice = model.lattice_constant(potential["a"])
    return {
        "lattice_constant": lattice,
        "cohesive_energy_per_atom": -model.bulk_energy(lattice) / atoms_per_site,
        "surface_energy_100": model.surface_energy_100(lattice) * EV_PER_A2_IN_J_PER_M2,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("potentials", nargs="+", help="sutton_chen potential YAML files")
    ap.add_argument("--atoms-per-site", type=float, default=8.0,
                    help="atoms a site stands for, for the cohesive energy per atom (default 8)")
    args = ap.parse_args()
    for path in args.potentials:
        potential = yaml.safe_load(open(path))
        if potential.get("style") != "sutton_chen":
            sys.exit(f"{path}: not a sutton_chen potential")
        d = describe(potential, args.atoms_per_site)
        print(f"{path}: static lattice constant {d['lattice_constant']:.4f} Å, cohesive energy "
              f"{d['cohesive_energy_per_atom']:.3f} eV/atom, (100) surface energy "
              f"{d['surface_energy_100']:.3f} J/m^2")


if __name__ == "__main__":
    main()
