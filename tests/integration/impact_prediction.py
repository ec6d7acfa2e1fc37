"""The front speed a dpd_uniaxial_strain stage predicts at a measured
particle velocity (docs/dpd-driver.md, "Impact").

The stage's table holds, for increasing compressions of the crystal with
its sides held, the particle velocity u_p and shock speed U_s of the
Rayleigh line to each state, and front_speed, the largest U_s up to that
state. A front that brings the target to u_p is led by the shock of largest
U_s among the states up to u_p: U_s(u_p) itself where U_s grows with
amplitude, the tangent state's where a softening sigma_xx(eps) splits the
wave. Between tabulated states U_s is interpolated linearly in u_p."""
import h5py
import numpy as np


def rayleigh_table(results_h5, stage):
    g = h5py.File(results_h5, "r")[stage]["uniaxial_strain"]
    return {k: np.asarray(g[k][:]) for k in ("compression", "particle_velocity", "shock_speed")}


def predicted_front_speed(table, u_p):
    """(leading-front speed, single-shock U_s at u_p), m/s; u_p in m/s.
    Raises ValueError where u_p lies outside the table's range of u_p
    (or where the table's u_p is not increasing up to it)."""
    u, us = table["particle_velocity"], table["shock_speed"]
    if not (u[0] <= u_p <= u[-1]):
        raise ValueError(f"u_p = {u_p:.1f} m/s outside the table's {u[0]:.1f}-{u[-1]:.1f} m/s")
    k = int(np.searchsorted(u, u_p))  # first state with u >= u_p
    if np.any(np.diff(u[: k + 1]) <= 0):
        raise ValueError("the table's u_p does not increase up to the measured one")
    if k == 0:
        at_u_p = us[0]
    else:
        w = (u_p - u[k - 1]) / (u[k] - u[k - 1])
        at_u_p = us[k - 1] + w * (us[k] - us[k - 1])
    return max(at_u_p, float(us[:k].max()) if k else at_u_p), at_u_p
