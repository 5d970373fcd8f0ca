"""Independent kinematics of a four-hinge mechanism, for tests.

A second code path, voussoir by voussoir, that shares nothing with archquake.fourlink.mechanism
except the arch geometry and the hinge points: instantaneous centres for velocities at the
undisplaced configuration, a Newton solution of the loop equation for displaced configurations, and
rigid motions of every voussoir.
"""

import numpy as np

from archquake.geometry import Hinge


def nominal_hinges(paper):
    table = paper["table1"]["NA"]
    return tuple(Hinge(j, f) for j, f in zip(table["joints"], table["faces"], strict=True))


def mirrored_hinges(arch, hinges):
    """Hinges of a mechanism of the mirrored arch, on the original arch (left to right)."""
    n = arch.n_voussoirs
    return tuple(Hinge(n - h.joint, h.face) for h in reversed(hinges))


def perp(v):
    v = np.asarray(v, dtype=float)
    return np.stack((-v[..., 1], v[..., 0]), axis=-1)


def instantaneous_velocities(arch, hinges, spin=1.0):
    """Centroid velocities (n, 2) and spins (n,) of the voussoirs when the block left of the
    second hinge turns about the first hinge with angular velocity ``spin``: block 2 turns about
    the intersection O of lines AB and CD."""
    a, b, c, d = (h.point(arch) for h in hinges)
    s, u = np.linalg.solve(np.array([b - a, -(c - d)]).T, d - a)  # O = a + s(b-a) = d + u(c-d)
    o = a + s * (b - a)
    w1 = spin
    w2 = w1 / (1.0 - s)  # w1 perp(b - a) = w2 perp(b - o), b - o = (1 - s)(b - a)
    w3 = w2 * (1.0 - u)  # w2 perp(c - o) = w3 perp(c - d), c - o = (1 - u)(c - d)
    ja, jb, jc, jd = (h.joint for h in hinges)
    g = arch.centroids
    v = np.zeros_like(g)
    w = np.zeros(arch.n_voussoirs)
    for lo, hi, pivot, spin_k in ((ja, jb, a, w1), (jb, jc, o, w2), (jc, jd, d, w3)):
        v[lo:hi] = spin_k * perp(g[lo:hi] - pivot)
        w[lo:hi] = spin_k
    return v, w


def virtual_work_multiplier(arch, hinges):
    """Load multiplier k of the mechanism by virtual work: horizontal forces k m g balance the
    weights, k sum m v_x = sum m v_y for any (virtual) velocity field of the mechanism."""
    v, _ = instantaneous_velocities(arch, hinges)
    m = arch.masses
    return float(np.sum(m * v[:, 1]) / np.sum(m * v[:, 0]))


def _angle(v):
    return np.arctan2(v[1], v[0])


def _loop_angles(a, d, ab, bc, cd, theta, guess):
    """Newton solution of A + AB e(theta) + BC e(t2) = D + CD e(t3) for (t2, t3)."""
    t2, t3 = guess
    for _ in range(60):
        r = (a + ab * np.array([np.cos(theta), np.sin(theta)])
             + bc * np.array([np.cos(t2), np.sin(t2)])
             - d - cd * np.array([np.cos(t3), np.sin(t3)]))
        jac = np.array([[-bc * np.sin(t2), cd * np.sin(t3)], [bc * np.cos(t2), -cd * np.cos(t3)]])
        step = np.linalg.solve(jac, -r)
        t2, t3 = t2 + step[0], t3 + step[1]
        if np.max(np.abs(step)) < 1e-15:
            break
    return t2, t3


class Configurations:
    """Displaced configurations of a mechanism, by continuation from the undisplaced one."""

    def __init__(self, arch, hinges):
        self.arch = arch
        self.hinges = hinges
        a, b, c, d = (h.point(arch) for h in hinges)
        self.a, self.b0, self.d = a, b, d
        self.ab, self.bc, self.cd = (np.hypot(*v) for v in (b - a, c - b, c - d))
        self.theta_u, self.t2_u, self.t3_u = _angle(b - a), _angle(c - b), _angle(c - d)
        ja, jb, jc, jd = (h.joint for h in hinges)
        self.blocks = ((ja, jb), (jb, jc), (jc, jd))

    def link_angles(self, theta, steps=200):
        guess = (self.t2_u, self.t3_u)
        for t in np.linspace(self.theta_u, theta, steps)[1:]:
            guess = _loop_angles(self.a, self.d, self.ab, self.bc, self.cd, t, guess)
        return guess

    def voussoirs(self, theta, guess):
        """Centroids (n, 2) and rotations (n,) of all voussoirs at ``theta`` (given a close guess
        of the link angles), and the refined link angles."""
        t2, t3 = _loop_angles(self.a, self.d, self.ab, self.bc, self.cd, theta, guess)
        b = self.a + self.ab * np.array([np.cos(theta), np.sin(theta)])
        rotations = (theta - self.theta_u, t2 - self.t2_u, t3 - self.t3_u)
        pivots_now = (self.a, b, self.d)
        pivots_then = (self.a, self.b0, self.d)
        g0 = self.arch.centroids
        g = np.full_like(g0, np.nan)
        rot = np.zeros(self.arch.n_voussoirs)
        for (lo, hi), delta, p_now, p_then in zip(self.blocks, rotations, pivots_now, pivots_then,
                                                 strict=True):
            c, s = np.cos(delta), np.sin(delta)
            rel = g0[lo:hi] - p_then
            g[lo:hi] = p_now + np.stack((c * rel[:, 0] - s * rel[:, 1],
                                         s * rel[:, 0] + c * rel[:, 1]), axis=-1)
            rot[lo:hi] = delta
        fixed = np.isnan(g[:, 0])
        g[fixed] = g0[fixed]
        return g, rot, (t2, t3)
