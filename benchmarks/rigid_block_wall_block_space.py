"""The contact problem of a wall solved in the blocks' velocities: accuracy and size, beside the
band solver of the impulses.

    python benchmarks/rigid_block_wall_block_space.py [--courses 10] [--blocks 19]

An analysis of a faster formulation, not yet the driver's path
(:func:`archquake.rigid_blocks.block_space.solve_states`, compiled): the wall's first step
under a 0.3 g ground acceleration (every contact closed, at rest) is solved by the active-set
method of :func:`archquake.rigid_blocks.contact_problem.solve_active_set` (the band solver of the
impulses), and the linear system of its final states is solved again in two other ways:

- dense, by LAPACK (``numpy.linalg.solve``) on the Delassus system of the impulses,
  :math:`(H_s M^{-1} H_g^T + R)\\,p = r` (``H_s`` the rows the states hold, ``H_g`` the directions
  of the impulses: the normal plus ``sigma mu`` times the tangent for a sliding contact; ``R``
  the compliance, ``rho`` times the diagonal of ``W``);
- in the blocks' velocities (numpy, and compiled: ``solve_states``, timed against the band
  solver's mean solve of the same step), by the Sherman-Morrison-Woodbury identity,
  :math:`\\Delta v = K^{-1} H_g^T R^{-1} r`, :math:`K = M + H_g^T R^{-1} H_s` (3 unknowns a
  block instead of 2 a contact), :math:`p = R^{-1}(r - H_s \\Delta v)`, refined iteratively on
  the residual of the impulses' system (the difference ``r - H_s dv`` cancels to the compliance,
  so the first solve is good to 1e-4 only).

Printed: the sizes and condition numbers of both systems, and at each refinement the backward
error, the largest difference of the impulses from the band solver's (relative to the largest
impulse) and of the velocity changes :math:`M^{-1} H_g^T p`. Measured on the 195-block wall
(10 courses of 19): ``K`` 585 x 585, condition 2.5e3, against 1576 impulses, condition 2e10;
after two refinements the velocities agree with the band solver's to 5e-14 and the impulses to
2e-7, as close as LAPACK's dense solve agrees with the band solver (6e-7): the statically
indeterminate part of the impulses, fixed only by the compliance (1e-9), is known to
:math:`\\epsilon / \\rho` by any of the three. The compiled solve (half-bandwidth 47 in the
blocks renumbered by reverse Cuthill-McKee: 1.3e6 operations a factorisation against 6.4e7)
took 0.76 ms against 8.3 ms for a solve of the band solver: 11 times faster per solve.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from archquake.geometry import GRAVITY  # noqa: E402
from archquake.geometry.assembly import wall as geometry_wall  # noqa: E402
from archquake.rigid_blocks import from_block_assembly  # noqa: E402
from archquake.rigid_blocks.block_space import solve_states  # noqa: E402
from archquake.rigid_blocks.contact_problem import (  # noqa: E402
    REGULARISATION,
    incidence,
    solve_active_set,
)
from archquake.rigid_blocks.contacts import FRICTION, contact_geometry  # noqa: E402
from archquake.rigid_blocks.dynamics import contact_arrays, time_step_for  # noqa: E402


def first_step(courses: int, blocks: int):
    """The contact problem of the wall's first step under 0.3 g, solved by the band solver."""
    wall = from_block_assembly(geometry_wall(courses, blocks, 0.4, 0.2, friction=0.6))
    arrays = contact_arrays(wall)
    bodies, contacts, cb = arrays["bodies"], arrays["contacts"], arrays["contact_bodies"]
    nb, nc = bodies.shape[0], contacts.shape[0]
    h = 2 * time_step_for(wall)  # a coarse step
    q = np.zeros((nb, 3))
    gap, slip, valid, jac = np.zeros(nc), np.zeros(nc), np.zeros(nc, bool), np.zeros((nc, 12))
    contact_geometry(q, bodies, contacts, cb, np.empty((nb, 2)), gap, slip, valid, jac)
    inv_mass = np.empty((nb, 4))
    inv_mass[:, 0], inv_mass[:, 1] = 1 / bodies[:, 0], 1 / bodies[:, 1]
    inv_mass[:, 2], inv_mass[:, 3] = np.sqrt(inv_mass[:, 0]), np.sqrt(inv_mass[:, 1])
    v_free = np.zeros((nb, 3))
    v_free[:, 0] = -0.3 * GRAVITY * h
    v_free[:, 1] = -GRAVITY * h
    mu = np.where(np.isnan(contacts[:, FRICTION]), 0.6, contacts[:, FRICTION])
    pointer, incident, half = incidence(cb, nb)
    kl = 2 * half + 1
    work = (np.zeros(nc, dtype=np.int64), np.zeros(nc, dtype=np.int64), pointer, incident, kl,
            np.zeros((2 * nc, kl + 1)), np.zeros((2 * nc, 3 * kl + 1)), np.zeros(2 * nc),
            np.zeros(2 * nc), np.zeros(2 * nc), np.zeros((nc, 12)))
    mass = bodies[:, 0].mean()
    v, impulse, state = v_free.copy(), np.zeros((nc, 2)), -np.ones(nc, dtype=np.int64)
    start = time.perf_counter()
    solves, converged = solve_active_set(v, inv_mass, cb, jac, valid, impulse, state, mu,
                                         1e-12 * mass * GRAVITY * h,
                                         REGULARISATION * GRAVITY * h, work, 60)
    elapsed = time.perf_counter() - start
    return dict(nb=nb, cb=cb, jac=jac, inv_mass=inv_mass, v_free=v_free, impulse=impulse,
                state=state, mu=mu, kl=kl, solves=solves, converged=converged, elapsed=elapsed)


def compare(p) -> None:
    """The final states' system solved densely and in the blocks' velocities (module doc)."""
    nb, cb, jac, st = p["nb"], p["cb"], p["jac"], p["state"]
    nc = cb.shape[0]
    big_h = np.zeros((2 * nc, 3 * nb))
    for c in range(nc):
        for side, first in ((0, 0), (1, 6)):
            body = cb[c, side]
            if body >= 0:
                big_h[2 * c, 3 * body:3 * body + 3] = jac[c, first:first + 3]
                big_h[2 * c + 1, 3 * body:3 * body + 3] = jac[c, first + 3:first + 6]
    minv = np.repeat(p["inv_mass"][:, :2], (2, 1), axis=1).reshape(-1)
    diag_w = np.einsum("ij,j,ij->i", big_h, minv, big_h)
    hs, hg, rd, old = [], [], [], []
    for c in np.flatnonzero(st > 0):
        if st[c] == 1:
            for k in (0, 1):
                hs.append(big_h[2 * c + k])
                hg.append(big_h[2 * c + k])
                rd.append(REGULARISATION * diag_w[2 * c + k])
                old.append(p["impulse"][c, k])
        else:
            sigma = p["mu"][c] * (1.0 if st[c] == 2 else -1.0)
            hs.append(big_h[2 * c])
            hg.append(big_h[2 * c] + sigma * big_h[2 * c + 1])
            rd.append(REGULARISATION * diag_w[2 * c])
            old.append(p["impulse"][c, 0])
    hs, hg, rd, old = np.array(hs), np.array(hg), np.array(rd), np.array(old)
    r = -hs @ p["v_free"].reshape(-1)
    k_matrix = np.diag(1 / minv) + hg.T @ (hs / rd[:, None])
    a_matrix = hs @ (minv[:, None] * hg.T) + np.diag(rd)
    print(f"impulses: {a_matrix.shape[0]} unknowns, condition {np.linalg.cond(a_matrix):.2e}; "
          f"blocks: {k_matrix.shape[0]} unknowns, condition {np.linalg.cond(k_matrix):.2e}")
    dv_old = minv * (hg.T @ old)

    def woodbury(rhs):
        return (rhs - hs @ np.linalg.solve(k_matrix, hg.T @ (rhs / rd))) / rd

    def report(name, x, berr=None):
        dp = np.abs(x - old).max() / np.abs(old).max()
        dv = np.abs(minv * (hg.T @ x) - dv_old).max() / np.abs(dv_old).max()
        extra = "" if berr is None else f", backward error {berr:.1e}"
        print(f"  {name:<22} impulses {dp:.1e}, velocity changes {dv:.1e}{extra}")

    report("dense (LAPACK)", np.linalg.solve(a_matrix, r))
    position, kb = block_numbering(p)
    compliance = REGULARISATION * diag_w.reshape(-1, 2)
    args = (p["v_free"], p["inv_mass"], p["cb"], jac, st, p["mu"], compliance, position, kb)
    solve_states(*args)  # JIT
    times = []
    for _ in range(5):
        start = time.perf_counter()
        impulse, _, refinements, berr = solve_states(*args)
        times.append(time.perf_counter() - start)
    compiled = np.array([impulse[c, k] for c in np.flatnonzero(st > 0)
                         for k in ((0, 1) if st[c] == 1 else (0,))])
    report(f"compiled, {refinements} refined", compiled, berr)
    band = p["elapsed"] / p["solves"]
    print(f"  compiled solve in the blocks' velocities: {1e3 * np.median(times):.2f} ms "
          f"(median of 5; half-bandwidth {kb}) against {1e3 * band:.2f} "
          f"ms a solve of the band solver: ratio {band / np.median(times):.1f}")
    x = woodbury(r)
    for refinement in range(4):
        y = minv * (hg.T @ x)
        residual = r - (hs @ y + rd * x)
        size = np.abs(r) + np.abs(hs) @ (minv * (np.abs(hg).T @ np.abs(x))) + rd * np.abs(x)
        report(f"blocks, refined {refinement}x", x, (np.abs(residual) / size).max())
        x = x + woodbury(residual)


def block_numbering(p) -> tuple[np.ndarray, int]:
    """The blocks' positions by reverse Cuthill-McKee and the half-bandwidth of ``K``."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    cb = p["cb"][(p["cb"] >= 0).all(axis=1)]
    nb = p["nb"]
    graph = csr_matrix((np.ones(len(cb)), (cb[:, 0], cb[:, 1])), shape=(nb, nb))
    graph = graph + graph.T
    order = reverse_cuthill_mckee(graph.tocsr(), symmetric_mode=True)
    position = np.empty(nb, dtype=np.int64)
    position[order] = np.arange(nb)
    return position, 3 * int(np.abs(position[cb[:, 0]] - position[cb[:, 1]]).max()) + 2


def band_cost(p) -> tuple[float, float]:
    """``n kl^2`` of the band factorisation of the impulses (2 per active contact) and of ``K``
    with the blocks renumbered by reverse Cuthill-McKee (3 unknowns a block)."""
    kb = block_numbering(p)[1]
    m = int((p["state"] >= 0).sum())
    return 2 * m * p["kl"] ** 2, 3 * p["nb"] * kb**2


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--courses", type=int, default=10)
    parser.add_argument("--blocks", type=int, default=19, help="blocks per course")
    args = parser.parse_args(argv)
    first_step(2, 2)  # JIT
    p = first_step(args.courses, args.blocks)
    active = int((p["state"] >= 0).sum())
    print(f"{p['nb']} blocks, {active} active contacts ({int((p['state'] == 0).sum())} open, "
          f"{int((p['state'] >= 2).sum())} sliding), impulse half-bandwidth {p['kl']}; band "
          f"solver: {p['solves']} solves in {1e3 * p['elapsed']:.1f} ms, converged "
          f"{p['converged']}")
    print(f"operations of one factorisation (n kl^2): impulses {band_cost(p)[0]:.3g}, blocks "
          f"renumbered by reverse Cuthill-McKee {band_cost(p)[1]:.3g}")
    print("largest difference from the band solver's solution (relative):")
    compare(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
