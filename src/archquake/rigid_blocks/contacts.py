r"""Contacts of rigid blocks: the packed arrays, the contact geometry, and the relative
velocities, impulses and Delassus blocks of single contacts.

The driver (:func:`archquake.rigid_blocks.solver.run`) evaluates :func:`contact_geometry` at
the start of every step; it and the contact problem (:mod:`archquake.rigid_blocks.contact_problem`)
reach the velocities of the contacts through :func:`relative_velocity`, :func:`apply_impulse`
and :func:`delassus_block`, which numba inlines into them. The frame, the displacements ``q``
and the velocities ``v`` of the blocks are those of the driver
(:mod:`archquake.rigid_blocks.solver`, "Frame and unknowns").

Contacts and their detection
----------------------------
Each joint ``j`` between bodies ``a`` and ``b`` has a contact at each of its two ends
``k = 0, 1`` (contact ``2 j + k``). The contact follows two material points, one of each body,
that coincide with the end of the joint in the undeformed configuration: ``p_a`` (on body ``a``)
and ``p_b`` (on body ``b``). The face of body ``a`` is the joint segment carried by ``a``, with
normal ``n_a`` and tangent ``t_a``. With ``c`` a centroid in the deformed configuration, ``r``
the undeformed offset of the contact point from it and ``R`` the rotation matrix (the ground
has ``theta = 0`` and ``c = 0``), the gap and the tangential offset of the contact are

.. math::

    p_a = c_a + R(\theta_a)\,r_a, \quad p_b = c_b + R(\theta_b)\,r_b, \quad
    n_a = R(\theta_a)\,n_j, \quad t_a = R(\theta_a)\,t_j,

    g = (p_b - p_a) \cdot n_a, \qquad s = (p_b - p_a) \cdot t_a

[m] exactly, for any rotation (nothing is linearised). This is the corner-to-face contact of
two convex polygons that touch along a common flat face: while the two faces are in contact or
turn about one end (a hinge), that end is a material point of both blocks, so the pair of
points stays exact at large rotations; the other end lifts off (``g > 0``) and lands again.
Only sliding moves ``p_b`` along the face; the contact holds (is *valid*) while the projection
of ``p_b`` on the face lies on the face of body ``a``,

.. math::

    \ell_{lo} \le o_k + s \le \ell_{hi}

with :math:`o_k` the position of the end along the joint (0 or its length) [m] and
:math:`[\ell_{lo}, \ell_{hi}]` the face (:attr:`Assembly.face_extents`: by default the joint
extended by 10 % of its length at each end, since beyond its end the exact contact would be
the corner of ``a`` on the face of ``b``, which differs to second order only, slip times
relative rotation).
Contacts of other faces (an extrados on a neighbouring block) are not detected: they cannot
occur before an arch collapses.

The normal and tangential relative velocities are the exact time derivatives of ``g`` and
``s``, ``u_n = H_n v`` and ``u_t = H_t v``, whose rows (the Jacobian ``H``) are, with the planar
cross product :math:`r \times n = r_x n_y - r_y n_x`,

.. math::

    H_{n,a} = -\bigl(n_a^T,\; (p_b - c_a) \times n_a\bigr), \qquad
    H_{n,b} = \bigl(n_a^T,\; (p_b - c_b) \times n_a\bigr)

and the same with ``t_a`` for ``H_t``: the turning of the face of ``a`` moves the lever arm of
body ``a`` from ``p_a`` to ``p_b`` (:func:`contact_geometry`).

Curved faces
------------
Two blocks that touch along an arc of a circle (the interface of two rings of an arch) share
one joint whose face of body ``a`` is that arc, of signed curvature :math:`\kappa` (> 0: the
face of ``a`` is convex, its centre inside ``a``; < 0: concave) [1/m], with a contact at each
end of the arc. With ``n_a`` the face's normal at the contact's end (radial) and
:math:`\sigma = \operatorname{sign}\kappa`, :math:`R = 1/|\kappa|`, the face's centre
``o``, the gap, the arc length and the normal at the contact are

.. math::

    o = p_a - \sigma R\, n_a, \qquad g = \sigma\,(\lVert p_b - o \rVert - R), \qquad
    s = \sigma R\, \angle(p_a - o,\; p_b - o), \qquad
    n = \sigma\,\frac{p_b - o}{\lVert p_b - o \rVert}

(the angle counterclockwise), and ``t`` is ``n`` turned by +90 degrees; the Jacobian rows are
those above with this ``n`` and ``t``. The gap is exact for any motion, and so is
:math:`u_n = H_n v = \dot g`: the velocity of ``o`` and that of the point of ``a`` at ``p_b``
differ by a rotation about ``o``, normal to ``n``. ``u_t`` is the slip rate at ``p_b``, the
rate of ``s`` while the contact is closed. Two end contacts hold a circular interface exactly
to first order: a rigid relative motion moves the face's points normal to it at the velocity
of the centre projected on the radial, :math:`u_n(\varphi) = V_o \cdot n(\varphi)`, a
cosine of the angle that is >= 0 over an arc shorter than a half circle where it is >= 0 at
both ends; so the ends admit the relative motions that the whole arc admits, rotation about
``o`` (the rings sliding on each other) among them, and nothing else. Cut into chords, the
same interface would need a contact at every chord's end, and the rings could not slide on
each other without opening at every chord's corner (by half the angle between two chords).
"""

from __future__ import annotations

import math

import numba
import numpy as np

BODY_FIELDS = ("mass", "inertia", "centroid_x", "centroid_y")
"""Columns of the body array ``bodies`` (nb, 4): mass [kg/m], polar moment of inertia [kg m] and
undeformed centroid [m] of every block."""

BODY_MASS, BODY_INERTIA, BODY_X, BODY_Y = range(4)

CONTACT_FIELDS = ("ra_x", "ra_y", "rb_x", "rb_y", "normal_x", "normal_y", "tangent_x",
                  "tangent_y", "offset", "face_lo", "face_hi", "length", "friction", "curvature")
"""Columns of the contact array ``contacts`` (nc, 14), contact ``2 j + k`` being end ``k`` of joint
``j``: the undeformed contact point relative to the centroid of body a and of body b (absolute for
the ground) [m], the joint's unit normal and tangent [-], the position of the end along the joint
(0 or its length), the face of body a along the joint and the joint's length [m], and the
joint's own Coulomb coefficient [-] (nan: the analysis's, ``BlockSettings.friction``) and the
signed curvature of the face of body a [1/m] (0: flat; "Curved faces" in the module docstring).
For a curved face the normal and tangent are those at the contact's end, and the positions
along the face are arc lengths [m]. The bodies
themselves are the int array ``contact_bodies`` (nc, 2): ``(a, b)``, -1 for the ground."""

(RA_X, RA_Y, RB_X, RB_Y, N_X, N_Y, T_X, T_Y, OFFSET, FACE_LO, FACE_HI, LENGTH, FRICTION,
 CURVATURE) = range(14)

# ---------------------------------------------------------------------------------------------
# Contacts: geometry, relative velocities, impulses
# ---------------------------------------------------------------------------------------------

@numba.njit(cache=True, inline="always")
def rotate(c, s, x, y):
    """``(x, y)`` turned by the angle whose cosine and sine are ``c, s`` [-] (same units)."""
    return c * x - s * y, s * x + c * y


@numba.njit(cache=True, _nrt=False)
def contact_geometry(q, bodies, contacts, contact_bodies, trig, gap, slip, valid, jac):
    r"""Gap [m], tangential offset [m], validity and Jacobian rows of every contact at ``q``.

    Evaluates, for every contact ``c`` (module docstring, "Contacts and their detection"),

    .. math::

        g = (p_b - p_a) \cdot n_a, \qquad s = (p_b - p_a) \cdot t_a, \qquad
        \text{valid} \iff \ell_{lo} \le o + s \le \ell_{hi},

        H_{n,a} = -\bigl(n_a^T,\; (p_b - c_a) \times n_a\bigr), \quad
        H_{n,b} = \bigl(n_a^T,\; (p_b - c_b) \times n_a\bigr),

    and the same with ``t_a`` for ``H_t``: a contact is valid while the projection of its
    point of body b on the face of body a, ``offset + slip`` along the face from the joint's
    first end [m], lies in ``[face_lo, face_hi]`` [m]. ``jac[c]`` holds ``(Gn_a, Gt_a, Gn_b,
    Gt_b)``, each a row of 3 so that the normal and tangential relative velocities are
    ``u_n = Gn_a . v_a + Gn_b . v_b`` (same for ``t``) [m/s]; the rows of the ground are 0.

    Parameters
    ----------
    q : array (nb, 3)
        Displacements ``(x, y, theta)`` of the blocks [m, m, rad].
    bodies : array (nb, 4)
        The blocks (:data:`BODY_FIELDS`).
    contacts : array (nc, 14)
        The contacts (:data:`CONTACT_FIELDS`).
    contact_bodies : array of int (nc, 2)
        Bodies a and b of every contact (-1 for the ground).
    trig : array (nb, 2)
        Work space: the cosine and sine of every block's rotation [-].
    gap, slip : array (nc,)
        Output: ``g`` and ``s`` [m].
    valid : array of bool (nc,)
        Output: whether the contact holds.
    jac : array (nc, 12)
        Output: Jacobian rows [-, -, m] per body and direction.
    """
    for i in range(q.shape[0]):
        trig[i, 0] = math.cos(q[i, 2])
        trig[i, 1] = math.sin(q[i, 2])
    for c in range(contacts.shape[0]):
        a, b = contact_bodies[c, 0], contact_bodies[c, 1]
        if a >= 0:
            cos_a, sin_a = trig[a, 0], trig[a, 1]
            xa, ya = rotate(cos_a, sin_a, contacts[c, RA_X], contacts[c, RA_Y])
            cax, cay = bodies[a, BODY_X] + q[a, 0], bodies[a, BODY_Y] + q[a, 1]
            pax, pay = cax + xa, cay + ya
            nx, ny = rotate(cos_a, sin_a, contacts[c, N_X], contacts[c, N_Y])
            tx, ty = rotate(cos_a, sin_a, contacts[c, T_X], contacts[c, T_Y])
        else:
            cax = cay = 0.0
            pax, pay = contacts[c, RA_X], contacts[c, RA_Y]
            nx, ny = contacts[c, N_X], contacts[c, N_Y]
            tx, ty = contacts[c, T_X], contacts[c, T_Y]
        if b >= 0:
            xb, yb = rotate(trig[b, 0], trig[b, 1], contacts[c, RB_X], contacts[c, RB_Y])
            cbx, cby = bodies[b, BODY_X] + q[b, 0], bodies[b, BODY_Y] + q[b, 1]
            pbx, pby = cbx + xb, cby + yb
        else:
            cbx = cby = 0.0
            pbx, pby = contacts[c, RB_X], contacts[c, RB_Y]
        dx, dy = pbx - pax, pby - pay
        kappa = contacts[c, CURVATURE]
        if kappa == 0.0:
            gap[c] = dx * nx + dy * ny
            slip[c] = dx * tx + dy * ty
        else:  # a circular face: the centre, then the radial normal through p_b
            side = 1.0 if kappa > 0.0 else -1.0
            radius = 1.0 / abs(kappa)
            ox, oy = pax - side * radius * nx, pay - side * radius * ny
            ex, ey = pbx - ox, pby - oy
            distance = math.hypot(ex, ey)
            gap[c] = side * (distance - radius)
            slip[c] = side * radius * math.atan2((pax - ox) * ey - (pay - oy) * ex,
                                                 (pax - ox) * ex + (pay - oy) * ey)
            nx, ny = side * ex / distance, side * ey / distance
            tx, ty = -ny, nx
        along = contacts[c, OFFSET] + slip[c]
        valid[c] = contacts[c, FACE_LO] <= along <= contacts[c, FACE_HI]
        # lever arms from each centroid to the contact point p_b
        rax, ray = pbx - cax, pby - cay
        rbx, rby = pbx - cbx, pby - cby
        if a >= 0:
            jac[c, 0] = -nx
            jac[c, 1] = -ny
            jac[c, 2] = -(rax * ny - ray * nx)
            jac[c, 3] = -tx
            jac[c, 4] = -ty
            jac[c, 5] = -(rax * ty - ray * tx)
        else:
            for k in range(6):
                jac[c, k] = 0.0
        if b >= 0:
            jac[c, 6] = nx
            jac[c, 7] = ny
            jac[c, 8] = rbx * ny - rby * nx
            jac[c, 9] = tx
            jac[c, 10] = ty
            jac[c, 11] = rbx * ty - rby * tx
        else:
            for k in range(6, 12):
                jac[c, k] = 0.0


@numba.njit(cache=True, inline="always")
def relative_velocity(v, a, b, jac, c):
    """Normal and tangential relative velocity ``(u_n, u_t)`` [m/s] of contact ``c`` between
    bodies ``a`` and ``b`` (-1: the ground) for block velocities ``v`` (nb, 3) [m/s, m/s,
    rad/s], through its Jacobian rows ``jac[c]`` (:func:`contact_geometry`).

    The indices are cast to unsigned integers once they are known to be >= 0: numba checks a
    signed index for wrapping around (a negative index counts from the end) at every access,
    which here cost as much as the arithmetic (so in the other helpers of every contact)."""
    uc = np.uint64(c)
    un = 0.0
    ut = 0.0
    if a >= 0:
        ua = np.uint64(a)
        va0, va1, va2 = v[ua, 0], v[ua, 1], v[ua, 2]
        un += jac[uc, 0] * va0 + jac[uc, 1] * va1 + jac[uc, 2] * va2
        ut += jac[uc, 3] * va0 + jac[uc, 4] * va1 + jac[uc, 5] * va2
    if b >= 0:
        ub = np.uint64(b)
        vb0, vb1, vb2 = v[ub, 0], v[ub, 1], v[ub, 2]
        un += jac[uc, 6] * vb0 + jac[uc, 7] * vb1 + jac[uc, 8] * vb2
        ut += jac[uc, 9] * vb0 + jac[uc, 10] * vb1 + jac[uc, 11] * vb2
    return un, ut


@numba.njit(cache=True, inline="always")
def apply_impulse(v, inv_mass, a, b, jac, c, pn, pt):
    """Add to the velocities ``v`` (nb, 3) [m/s, m/s, rad/s], in place, the change
    ``M^-1 H_c^T (pn, pt)`` that the impulses ``pn, pt`` [N s/m] of contact ``c`` give bodies
    ``a`` and ``b``; ``inv_mass`` (nb, >= 2) holds the inverse mass [m/kg] and inertia
    [1/(kg m)] of every block (unsigned indices: :func:`relative_velocity`)."""
    uc = np.uint64(c)
    if a >= 0:
        ua = np.uint64(a)
        im, ii = inv_mass[ua, 0], inv_mass[ua, 1]
        v[ua, 0] += im * (jac[uc, 0] * pn + jac[uc, 3] * pt)
        v[ua, 1] += im * (jac[uc, 1] * pn + jac[uc, 4] * pt)
        v[ua, 2] += ii * (jac[uc, 2] * pn + jac[uc, 5] * pt)
    if b >= 0:
        ub = np.uint64(b)
        im, ii = inv_mass[ub, 0], inv_mass[ub, 1]
        v[ub, 0] += im * (jac[uc, 6] * pn + jac[uc, 9] * pt)
        v[ub, 1] += im * (jac[uc, 7] * pn + jac[uc, 10] * pt)
        v[ub, 2] += ii * (jac[uc, 8] * pn + jac[uc, 11] * pt)


@numba.njit(cache=True, inline="always")
def delassus_block(inv_mass, a, b, jac, c):
    """The 2 x 2 Delassus block ``H_c M^-1 H_c^T`` of contact ``c`` (bodies ``a``, ``b``),
    ``(W_nn, W_nt, W_tt)`` [m/kg], from the inverse masses and inertias ``inv_mass`` (nb, >= 2)
    and the Jacobian rows ``jac[c]``."""
    wnn = wnt = wtt = 0.0
    for body, k in ((a, 0), (b, 6)):
        if body >= 0:
            im, ii = inv_mass[body, 0], inv_mass[body, 1]
            wnn += im * (jac[c, k] ** 2 + jac[c, k + 1] ** 2) + ii * jac[c, k + 2] ** 2
            wnt += (im * (jac[c, k] * jac[c, k + 3] + jac[c, k + 1] * jac[c, k + 4])
                    + ii * jac[c, k + 2] * jac[c, k + 5])
            wtt += im * (jac[c, k + 3] ** 2 + jac[c, k + 4] ** 2) + ii * jac[c, k + 5] ** 2
    return wnn, wnt, wtt
