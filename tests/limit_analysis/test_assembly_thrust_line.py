"""The line of thrust of an assembly at collapse (``AssemblyLimit.thrust_line``): for an arch it
is the static method's own (an independent formulation: a chain's joint forces from the
forces at its first joint, not the interfaces of an assembly's program), in a bridge every
block held by two interfaces has its two segments meet on its load's line (three forces in
equilibrium are concurrent), and blocks that carry more, or rings, draw none."""

import numpy as np
import pytest

from archquake import oppenheim
from archquake.geometry.spec import StructureSpec
from archquake.limit_analysis import assembly_limit, assembly_limits, limit_analysis


def kinks(thrust_line):
    """Where the joint force meets the load's line in every voussoir of the static method."""
    out = []
    for i in range(thrust_line.loads.shape[0]):
        p, f = thrust_line.points[i], thrust_line.forces[i]
        q, w = thrust_line.load_points[i], thrust_line.loads[i]
        cross = f[0] * w[1] - f[1] * w[0]
        rel = q - p
        out.append(p + (rel[0] * w[1] - rel[1] * w[0]) / cross * f)
    return np.array(out)


@pytest.mark.parametrize(("direction", "mirror"), [("+x", "l"), ("-x", "r")])
def test_the_arch_as_an_assembly_draws_the_static_methods_thrust_line(direction, mirror):
    arch = oppenheim()
    result = assembly_limit(arch, direction)
    segments, blocks = result.thrust_line()
    assert segments.shape == (2 * arch.n_voussoirs, 2, 2)
    np.testing.assert_array_equal(np.bincount(blocks), np.full(arch.n_voussoirs, 2))
    reference = limit_analysis(arch, mirror, "static").thrust_line
    expected = kinks(reference)
    if mirror == "r":  # the static method reports Mech-r in the mirrored frame
        expected = expected[::-1] * np.array([-1.0, 1.0])
    for i in range(arch.n_voussoirs):
        np.testing.assert_allclose(segments[blocks == i, 1], [expected[i]] * 2, atol=1e-6)


@pytest.mark.parametrize("spec", [StructureSpec(spans=3, piers="3,6"),
                                  StructureSpec(spans=3, piers="3,6", fill_cover=0.5,
                                                fill_density=1800.0)])
def test_a_bridges_blocks_held_by_two_interfaces_meet_on_their_loads_line(spec):
    for laws in assembly_limits(spec.nominal()).values():
        for result in laws.values():
            segments, blocks = result.thrust_line()
            c = result.contacts
            size = float(np.ptp(np.concatenate(c.outlines), axis=0).max())
            drawn = np.bincount(blocks, minlength=c.n_blocks)
            touching = [int(np.sum((c.a == j) | (c.b == j))) for j in range(c.n_blocks)]
            assert all(d == 2 for d, t in zip(drawn, touching, strict=True) if t == 2)
            assert all(d == 0 for d, t in zip(drawn, touching, strict=True) if t > 2)
            for j in np.flatnonzero(drawn == 2):
                ends = segments[blocks == j, 1]
                assert np.hypot(*(ends[0] - ends[1])) < 1e-9 * size
                # on the load's line through (a_j, b_j)
                sign = 1.0 if result.direction == "+x" else -1.0
                load = np.array([sign * result.load_multiplier * c.horizontal[j],
                                 -c.vertical[j]])
                rel = ends[0] - np.array([c.vertical_x[j], c.horizontal_y[j]])
                assert abs(rel[0] * load[1] - rel[1] * load[0]) < 1e-9 * size * np.hypot(*load)


def test_rings_share_their_thrust_and_draw_no_line():
    result = assembly_limits(StructureSpec(rings=2).nominal())["+x"]["no sliding"]
    segments, blocks = result.thrust_line()
    assert segments.shape == (0, 2, 2) and blocks.size == 0
