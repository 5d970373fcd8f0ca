"""Fill over an arch: the columns against integrals of the circular extrados, voussoir and
column as one body, the loads of each inertia model and the passive bounds."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from archquake.geometry import (
    GRAVITY,
    Fill,
    Structure,
    arch_on_piers,
    circular_arch,
    shaped_arch,
    surveyed_arch,
)
from archquake.geometry.fill import check_dynamic_fill, fill_columns
from archquake.geometry.mass import polygon_properties

R_OUT = 10.75  # extrados of Oppenheim's arch [m]


def column_integrals(x0, x1, level):
    """Area, first moments and polar moment about O of the region between the circle of radius
    R_OUT and the line y = level over [x0, x1], by quadrature in x."""
    def y(x):
        return math.sqrt(R_OUT**2 - x * x)

    area = quad(lambda x: level - y(x), x0, x1, epsabs=1e-13)[0]
    qx = quad(lambda x: x * (level - y(x)), x0, x1, epsabs=1e-13)[0]
    qy = quad(lambda x: 0.5 * (level**2 - y(x) ** 2), x0, x1, epsabs=1e-13)[0]
    j = quad(lambda x: x * x * (level - y(x)) + (level**3 - y(x) ** 3) / 3, x0, x1,
             epsabs=1e-12)[0]
    return area, qx, qy, j


def test_columns_of_oppenheim_arch_match_integrals(nominal):
    fill = Fill(0.5, 1600.0)
    columns = fill_columns(nominal, fill)
    assert columns.level == pytest.approx(R_OUT + 0.5)
    ends = -R_OUT * np.cos(nominal.joint_angles)  # x of the extrados ends, left to right
    for i in range(7):
        area, qx, qy, j = column_integrals(ends[i], ends[i + 1], columns.level)
        assert columns.masses[i] == pytest.approx(1600 * area, rel=1e-10)
        centroid = np.array([qx, qy]) / area
        assert columns.centroids[i] == pytest.approx(centroid, abs=1e-9)
        assert columns.inertias[i] == pytest.approx(1600 * (j - area * centroid @ centroid),
                                                    rel=1e-8)
        x = centroid[0]
        assert columns.extrados_points[i] == pytest.approx([x, math.sqrt(R_OUT**2 - x * x)])


def test_voussoir_and_column_are_one_body():
    """With the fill as dense as the masonry, a flat-faced voussoir and its column are one
    polygon: the structure's mass properties are that polygon's."""
    arch = shaped_arch("circular", span=12.0, rise=4.0, thickness=0.7, voussoirs=6,
                       faces="flat")
    s = Structure(arch, fill=Fill(0.8, arch.density))
    level = s.fill_columns.level
    for i in range(6):
        c = arch.outline(i)[:4]  # intrados left, intrados right, extrados right, extrados left
        union = [c[0], c[1], c[2], (c[2][0], level), (c[3][0], level), c[3]]
        mass, centroid, inertia = polygon_properties(union, arch.density)
        assert s.masses[i] == pytest.approx(mass, rel=1e-12)
        assert s.centroids[i] == pytest.approx(centroid, abs=1e-12)
        assert s.inertias[i] == pytest.approx(inertia, rel=1e-10)


def test_loads_of_each_inertia_model(nominal):
    """Weights of voussoir and column through their common centroid; horizontal loads: the
    masonry's alone (none), the common centroid (centroid), the column's on the extrados below
    its centroid (extrados)."""
    m, c = nominal.masses, nominal.centroids
    for inertia in ("none", "centroid", "extrados"):
        s = Structure(nominal, fill=Fill(0.5, 1600.0, inertia))
        col = s.fill_columns
        loads = s.loads
        assert loads.vertical == pytest.approx((m + col.masses) * GRAVITY)
        assert loads.vertical_x == pytest.approx(
            (m * c[:, 0] + col.masses * col.centroids[:, 0]) / (m + col.masses))
        if inertia == "none":
            assert loads.horizontal == pytest.approx(m * GRAVITY)
            assert loads.horizontal_y == pytest.approx(c[:, 1])
        elif inertia == "centroid":
            assert loads.horizontal == pytest.approx((m + col.masses) * GRAVITY)
            assert loads.horizontal_y == pytest.approx(s.centroids[:, 1])
        else:
            assert loads.horizontal_y == pytest.approx(
                (m * c[:, 1] + col.masses * col.extrados_points[:, 1]) / (m + col.masses))
        assert not loads.has_passive


def test_passive_bounds_by_hand(nominal):
    """Rankine: K_p = tan^2(45 + 15) = 3 for phi = 30 deg; on voussoir 0 the bound is
    m_p K_p gamma (y_top - y_mid) dy, toward +x; none on the crown voussoir (it straddles
    midspan); toward -x on the right."""
    fill = Fill(0.5, 1600.0, friction_angle=math.radians(30), mobilisation=0.33)
    assert fill.passive_coefficient == pytest.approx(3.0)
    col = fill_columns(nominal, fill)
    beta = nominal.joint_angles
    y0, y1 = R_OUT * math.sin(beta[0]), R_OUT * math.sin(beta[1])
    bound = 0.33 * 3.0 * 1600 * GRAVITY * (11.25 - 0.5 * (y0 + y1)) * (y1 - y0)
    assert col.passive[0] == pytest.approx(bound, rel=1e-12)
    assert col.passive_y[0] == pytest.approx(0.5 * (y0 + y1))
    assert col.passive_sign.tolist() == [1, 1, 1, 0, -1, -1, -1]
    assert col.passive[3] == 0 and col.passive[6] == pytest.approx(bound, rel=1e-12)
    assert col.extrados_range[3] == pytest.approx([R_OUT * math.sin(beta[3]), R_OUT])


def test_surveyed_arch_carries_the_same_fill(nominal):
    """The extrados of a surveyed block is its boundary between the joints' extrados ends: the
    sampled arch carries the circular arch's columns to the sampling error."""
    survey = surveyed_arch([nominal.outline(i, 400)[:-1] for i in range(7)])
    fill = Fill(0.5, 1600.0)
    exact, sampled = fill_columns(nominal, fill), fill_columns(survey, fill)
    assert sampled.masses == pytest.approx(exact.masses, rel=1e-5)
    assert sampled.centroids == pytest.approx(exact.centroids, abs=1e-5)


def test_fill_over_piers_covers_the_arch_only(nominal):
    s = arch_on_piers(nominal, 3.0, 6.0, fill=Fill(0.5, 1600.0))
    bare = arch_on_piers(nominal, 3.0, 6.0)
    assert s.masses[[0, -1]] == pytest.approx(bare.masses[[0, -1]])
    assert s.total_mass - bare.total_mass == pytest.approx(s.fill_columns.masses.sum())
    assert s.loads.passive.sum() == 0.0


def test_fill_errors():
    with pytest.raises(ValueError, match="cover must be in"):
        Fill(-0.1)
    with pytest.raises(ValueError, match="fill inertia must be one of"):
        Fill(0.5, inertia="top")
    with pytest.raises(ValueError, match="both friction_angle"):
        Fill(0.5, friction_angle=0.5)
    with pytest.raises(ValueError, match="mobilisation must be in"):
        Fill(0.5, friction_angle=0.5, mobilisation=2.0)
    with pytest.raises(ValueError, match="runs left to right"):
        Structure(circular_arch(10.0, math.radians(200), 1.5, 8), fill=Fill(0.5))
    with pytest.raises(ValueError, match="dynamic models carry the fill as mass"):
        check_dynamic_fill(Structure(circular_arch(10.0, 2.0, 1.0, 6), fill=Fill(0.5, 1600.0,
                                                                                  "none")))
