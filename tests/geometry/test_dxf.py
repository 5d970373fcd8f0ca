"""Drawings: a block assembly drawn and read back equal, units converted by the header, every
refused entity named by its handle and layer."""

import math
import warnings

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from archquake.geometry import load_arch  # noqa: E402
from archquake.geometry.assembly import GROUND, from_arch, portal, wall  # noqa: E402
from archquake.geometry.dxf import read_dxf, write_dxf  # noqa: E402


def drawing(path, polylines, insunits=6, layer="WALL"):
    """A DXF of closed LWPOLYLINEs ``(points, layer)`` (or ``points``), header $INSUNITS."""
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = insunits
    msp = doc.modelspace()
    handles = []
    for item in polylines:
        points, lay = item if isinstance(item, tuple) else (item, layer)
        fmt = "xyb" if len(points[0]) == 3 else "xy"
        e = msp.add_lwpolyline(points, format=fmt, close=True, dxfattribs={"layer": lay})
        handles.append(e.dxf.handle)
    doc.saveas(path)
    return handles


def rectangle(x0, y0, x1, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


@pytest.mark.parametrize("make", [lambda: wall(4, 3, 0.4, 0.2), lambda: portal(0.5, 2, 1.5, 0.4)],
                         ids=["wall", "portal"])
def test_round_trip_is_equal(tmp_path, make):
    a = make()
    write_dxf(a, tmp_path / "a.dxf")
    back = read_dxf(tmp_path / "a.dxf")
    assert back == a
    assert np.array_equal(back.interfaces.p0, a.interfaces.p0)


def test_round_trip_of_an_arch_keeps_its_polygons_and_supports(tmp_path, nominal):
    a = from_arch(nominal)
    write_dxf(a, tmp_path / "arch.dxf")
    back = read_dxf(tmp_path / "arch.dxf")
    assert all(np.array_equal(p, q) for p, q in zip(back.polygons, a.polygons, strict=True))
    assert all(np.array_equal(p, q) for p, q in zip(back.supports, a.supports, strict=True))
    assert back.support_names[0].endswith("layer SUPPORT")
    # without the builder's kinds, the joints near the crown are found as head joints: the
    # interfaces themselves are the same
    assert back.interfaces.n_interfaces == a.interfaces.n_interfaces == 8
    assert np.allclose(back.interfaces.p0, a.interfaces.p0, atol=1e-12)


@pytest.mark.parametrize("insunits, units, scale", [
    (4, None, 0.001), (5, None, 0.01), (6, None, 1.0), (1, None, 0.0254), (2, None, 0.3048),
    (4, "m", 1.0), (6, "mm", 0.001)])
def test_units_convert_to_metres(tmp_path, insunits, units, scale):
    # a block 400 x 200 drawing units on the ground: in mm, 0.4 m x 0.2 m, area 0.08 m^2
    drawing(tmp_path / "d.dxf", [rectangle(0, 0, 400, 200)], insunits)
    a = read_dxf(tmp_path / "d.dxf", units=units, density=1000.0)
    assert a.polygons[0].max(axis=0) == pytest.approx([400 * scale, 200 * scale], rel=1e-15)
    assert a.mass == pytest.approx([1000.0 * 400 * 200 * scale**2], rel=1e-14)


def test_unitless_drawing_is_taken_in_metres_with_a_warning(tmp_path):
    drawing(tmp_path / "d.dxf", [rectangle(0, 0, 2, 1)], insunits=0)
    with pytest.warns(UserWarning, match="unitless.*taken in metres"):
        a = read_dxf(tmp_path / "d.dxf")
    assert a.area == pytest.approx([2.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert read_dxf(tmp_path / "d.dxf", units="cm").area == pytest.approx([2e-4])


def test_support_layer_is_case_insensitive_and_carries_the_blocks(tmp_path):
    drawing(tmp_path / "d.dxf", [(rectangle(-1, -1, 3, 0), "Ground"), rectangle(0, 0, 1, 2),
                                 rectangle(1, 0, 2, 2)])
    a = read_dxf(tmp_path / "d.dxf")
    assert a.n_blocks == 2 and len(a.supports) == 1
    i = a.interfaces
    assert i.a[i.kind == "foundation"].tolist() == [GROUND, GROUND]
    assert i.length[i.kind == "foundation"] == pytest.approx([1.0, 1.0])


def test_bulges_are_refused_or_drawn_as_chords(tmp_path):
    """A 1 m x 0.5 m rectangle whose right side is an arc of bulge 0.5: the arc subtends
    theta = 4 atan(0.5) = 1.8546 rad on the chord c = 0.5 m, radius r = c / (2 sin(theta/2))
    = 0.3125 m, and adds the segment r^2/2 (theta - sin theta) = 0.04368 m^2 outward. Chords
    within e of the arc miss at most e times the arc's length r theta."""
    points = [(0, 0, 0), (1000, 0, 0.5), (1000, 500, 0), (0, 500, 0)]
    handle = drawing(tmp_path / "d.dxf", [points], insunits=4)[0]
    with pytest.raises(ValueError, match=f"LWPOLYLINE handle {handle}, layer WALL: vertex 1 "
                                         "starts an arc"):
        read_dxf(tmp_path / "d.dxf")
    theta = 4 * math.atan(0.5)
    r = 0.25 / math.sin(theta / 2)
    exact = 0.5 + r * r / 2 * (theta - math.sin(theta))
    error = 1e-3
    a = read_dxf(tmp_path / "d.dxf", arc_chord_error=error)
    assert exact - r * theta * error <= a.area[0] <= exact


def test_refused_entities_are_named(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 6
    msp = doc.modelspace()
    open_line = msp.add_lwpolyline(rectangle(0, 0, 1, 1), dxfattribs={"layer": "WALL"})
    doc.saveas(tmp_path / "open.dxf")
    with pytest.raises(ValueError, match=f"handle {open_line.dxf.handle}, layer WALL: an open "
                                         "polyline"):
        read_dxf(tmp_path / "open.dxf")

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 6
    circle = doc.modelspace().add_circle((0, 1), 1, dxfattribs={"layer": "STONES"})
    doc.saveas(tmp_path / "circle.dxf")
    with pytest.raises(ValueError, match=f"CIRCLE handle {circle.dxf.handle}, layer STONES: a "
                                         "curve"):
        read_dxf(tmp_path / "circle.dxf")

    handle = drawing(tmp_path / "two.dxf", [[(0, 0), (1, 0), (1, 0)]])[0]
    with pytest.raises(ValueError, match=f"handle {handle}, layer WALL: a block needs at least "
                                         "three"):
        read_dxf(tmp_path / "two.dxf")


def test_assembly_errors_name_the_entities(tmp_path):
    handles = drawing(tmp_path / "d.dxf", [rectangle(0, 0, 1, 1), rectangle(0, 0.5, 1, 1.5)])
    with pytest.raises(ValueError, match=rf"block 0 \(handle {handles[0]}, layer WALL\) and "
                                         rf"block 1 \(handle {handles[1]}, layer WALL\) overlap"):
        read_dxf(tmp_path / "d.dxf")


def test_other_entities_are_ignored_with_a_warning(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 6
    msp = doc.modelspace()
    msp.add_lwpolyline(rectangle(0, 0, 1, 1), close=True)
    msp.add_line((0, 0), (5, 5))
    msp.add_text("a note")
    doc.saveas(tmp_path / "d.dxf")
    with pytest.warns(UserWarning, match="1 LINE entities are ignored"):
        assert read_dxf(tmp_path / "d.dxf").n_blocks == 1


def test_bad_files_and_arguments(tmp_path):
    (tmp_path / "x.dxf").write_text("not a drawing")
    with pytest.raises(ValueError, match="cannot read the drawing"):
        read_dxf(tmp_path / "x.dxf")
    drawing(tmp_path / "d.dxf", [rectangle(0, 0, 1, 1)])
    with pytest.raises(ValueError, match="units must be one of"):
        read_dxf(tmp_path / "d.dxf", units="yd")
    with pytest.raises(ValueError, match="arc_chord_error must be"):
        read_dxf(tmp_path / "d.dxf", arc_chord_error=0.0)
    drawing(tmp_path / "s.dxf", [(rectangle(0, 0, 1, 1), "SUPPORT")])
    with pytest.raises(ValueError, match="holds no block"):
        read_dxf(tmp_path / "s.dxf")


def test_geometry_file_reader_reads_drawings(tmp_path):
    drawing(tmp_path / "d.dxf", [rectangle(0, 0, 400, 200)], insunits=4)
    a = load_arch(tmp_path / "d.dxf")
    assert a.area == pytest.approx([0.08])
    with pytest.raises(ValueError, match="geometry file .*d2.dxf.*cannot read"):
        load_arch(tmp_path / "d2.dxf")
