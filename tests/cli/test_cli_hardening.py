"""Command lines that used to give a silent wrong answer, invalid JSON or a traceback: each test
is named after what it guards."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from archquake.cli import main
from archquake.defaults import MAX_ACCELERATION_G
from archquake.studies.failure_domain import inclusive_range

DATA = Path(__file__).parents[1] / "data"


def _refuse_constant(name):
    raise AssertionError(f"{name} in the JSON output")


def strict_json(text):
    """``text`` parsed as strict JSON (no NaN, no Infinity)."""
    return json.loads(text, parse_constant=_refuse_constant)


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("archquake: error: "), err
    return err[0]


# --- ranges never pass their stop -------------------------------------------------------------

@pytest.mark.parametrize("start, stop, step, expected", [
    (0.2, 1.0, 0.3, [0.2, 0.5, 0.8]),  # 1.1 was scanned
    (0.2, 1.0, 0.2, [0.2, 0.4, 0.6, 0.8, 1.0]),
    (0.3, 0.5, 0.1, [0.3, 0.4, 0.5]),  # 0.3 + 2 * 0.1 = 0.5000000000000001
    (1.0, 1.0, 0.5, [1.0]),
    (0.0, 0.99999999, 0.5, [0.0, 0.5]),
])
def test_range_never_passes_its_stop(start, stop, step, expected):
    values = inclusive_range(start, stop, step)
    assert values.tolist() == pytest.approx(expected, abs=1e-12)
    assert values.max() <= stop


def test_range_includes_a_stop_it_lands_on_within_the_tolerance():
    values = inclusive_range(0.2, 1.0, 0.01)
    assert len(values) == 81 and values[-1] == 1.0
    assert np.all(np.diff(values) > 0)


def test_domain_scans_no_amplitude_beyond_the_stop(capsys):
    assert main(["domain", "--durations", "0.5", "--amplitudes", "0.2:1.0:0.3",
                 "--extend-to", "0", "--json"]) == 0
    (row,) = strict_json(capsys.readouterr().out)
    assert row["scanned_to"] == 0.8  # 1.1 was scanned
    assert max(iv["to"] for iv in row["intervals"]) == 0.8


def test_compare_range_error_names_a_value_of_the_range(capsys):
    """0.3:1001:1 holds 0.3, 1.3, ..., 1000.3; the error names the first value beyond the cap,
    not 1001.3, which the range does not hold."""
    assert main(["compare", "--amplitudes", "0.3:1001:1", "--durations", "0.5"]) == 2
    line = error_line(capsys)
    assert "1001.3" not in line and "--amplitudes" in line


# --- the 1000 g cap holds for scaled records --------------------------------------------------

@pytest.mark.parametrize("argv, level", [
    (["--levels", "1,2000"], "2000 g of pga"),
    (["--levels", "1", "--im", "sa(1e6)"], "1 g of sa(1e6)"),
])
def test_record_fragility_refuses_levels_beyond_the_acceleration_cap(capsys, tmp_path, argv,
                                                                    level):
    out = tmp_path / "study"
    assert main(["record-fragility", "--records", str(DATA / "decaying_sine.csv"), *argv,
                 "--samples", "2", "--out", str(out), "--no-progress"]) == 2
    line = error_line(capsys)
    assert f"--levels: the level {level}" in line
    assert "'decaying_sine.csv'" in line and f"{MAX_ACCELERATION_G:g} g" in line
    assert not out.exists() or not any(out.iterdir())


def test_record_suite_scale_factors_refuse_a_peak_beyond_the_cap():
    """The cap is on the scaled peak: the factor that brings the record's PGA to the cap is
    accepted, one just above it is not (the PGA of the file computed here from its samples)."""
    from archquake.ground_motion.suites import RecordSuite

    suite = RecordSuite.from_paths([DATA / "decaying_sine.csv"])
    _, a_g = np.loadtxt(DATA / "decaying_sine.csv", delimiter=",", skiprows=3, unpack=True)
    pga = float(np.max(np.abs(a_g)))
    factors = suite.scale_factors("pga", [MAX_ACCELERATION_G])
    assert factors[0, 0] * pga == pytest.approx(MAX_ACCELERATION_G, rel=1e-12)
    with pytest.raises(ValueError, match="levels: the level 1001 g of pga"):
        suite.scale_factors("pga", [1.0, 1001.0])
    assert math.isfinite(pga)


# --- a failure at the first amplitude scanned is a bound, not a value ------------------------

def test_domain_marks_a_collapse_from_the_first_amplitude_as_an_upper_bound(capsys):
    """t = 0.7 m: k = 0.058, and the arch already collapses at 0.2 g, the lowest amplitude
    scanned; a scan from 0.01 g finds the failure acceleration below 0.2 g, as the bound says."""
    argv = ["domain", "--thickness", "0.7", "--durations", "0.5"]
    assert main([*argv, "--amplitudes", "0.2:1:0.05"]) == 0
    out = capsys.readouterr().out
    assert "<= 0.2000" in out and "at most it" in out
    assert main([*argv, "--amplitudes", "0.2:1:0.05", "--json"]) == 0
    (row,) = strict_json(capsys.readouterr().out)
    assert row["failure_acceleration"] == 0.2 and row["failure_acceleration_bound"] == "upper"
    assert main([*argv, "--amplitudes", "0.01:1:0.01", "--json"]) == 0
    (fine,) = strict_json(capsys.readouterr().out)
    assert "failure_acceleration_bound" not in fine
    assert fine["failure_acceleration"] < 0.2


def test_domain_json_keeps_its_keys_when_the_failure_is_bracketed(capsys):
    assert main(["domain", "--durations", "0.5", "--amplitudes", "0.3:1:0.05", "--json"]) == 0
    (row,) = strict_json(capsys.readouterr().out)
    assert set(row) == {"duration", "failure_acceleration", "first_half_cycle_acceleration",
                        "scanned_to", "intervals", "model_check"}


@pytest.mark.parametrize("friction", ["0", "0.2"])
def test_compare_refuses_an_arch_that_slides_under_its_own_weight(capsys, friction):
    """Oppenheim's arch needs a friction of 0.206 to stand (limit analysis with friction);
    below it every amplitude 'collapses' it, and no failure acceleration is printed."""
    assert main(["compare", "--friction", friction, "--durations", "0.5", "--amplitudes",
                 "0.3:0.5:0.1", "--no-progress"]) == 2
    line = error_line(capsys)
    assert f"with friction {friction} at its joints the arch cannot stand" in line


# --- smaller ones ---------------------------------------------------------------------------

def test_rise_zero_is_a_rise_of_zero_not_a_missing_option(capsys):
    assert main(["limit", "--shape", "parabolic", "--span", "10", "--rise", "0"]) == 2
    assert "--rise must be a finite number > 0" in error_line(capsys)


def test_pointed_arch_takes_an_even_default_number_of_voussoirs(capsys):
    """7 (the default of the other shapes) is refused for a pointed arch: it takes 8."""
    assert main(["limit", "--shape", "pointed", "--span", "10", "--rise", "6"]) == 0
    assert "n = 8 voussoirs" in capsys.readouterr().out
    assert main(["limit", "--shape", "pointed", "--span", "10", "--rise", "6",
                 "--voussoirs", "7"]) == 2
    assert "divisible by 2" in error_line(capsys)


def test_free_vibration_beyond_the_point_of_no_return_prints_no_nan(capsys):
    assert main(["simulate", "--phi0", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "nan" not in out and "released beyond its point of no return" in out


def test_outcomes_of_identical_runs_are_equal_and_hash_alike():
    from archquake import FourLinkModel, oppenheim
    from archquake.ground_motion import oppenheim_pulse

    dynamics = FourLinkModel.from_arch(oppenheim())
    pulse = oppenheim_pulse(-0.3 * 9.81, 0.4)  # below k: rest, collapse_time nan
    a, b = dynamics.outcome(pulse), dynamics.outcome(pulse)
    assert math.isnan(a.collapse_time)
    assert a == b and hash(a) == hash(b)
    assert a != dynamics.outcome(oppenheim_pulse(-0.8 * 9.81, 0.4))


def test_study_settings_are_hashable_as_they_compare():
    from archquake.studies.fragility import FragilitySettings

    assert len({FragilitySettings(), FragilitySettings(), FragilitySettings(seed=1)}) == 2


def test_sigterm_stops_reproduce_like_ctrl_c(monkeypatch):
    """The report starts a process of its own: SIGTERM must stop it cleanly (its helper and
    queues released), not kill the report and leave them."""
    import signal

    from archquake.cli import _signals, main_reproduce

    seen = []
    monkeypatch.setattr(main_reproduce, "run",
                        lambda args: seen.append(signal.getsignal(signal.SIGTERM)) or 0)
    assert main(["reproduce", "--out", "unused"]) == 0
    assert seen == [_signals.raise_terminated]


def test_a_pulse_duration_of_days_is_refused_naming_the_option(capsys):
    """compare --durations 1e6 suggested a --t-end compare does not have."""
    assert main(["compare", "--durations", "1e6", "--no-progress"]) == 2
    line = error_line(capsys)
    assert "--durations must be pulse durations in (0, 60] s" in line and "t_end" not in line


@pytest.mark.parametrize("argv", [["fragility", "--out", ""], ["reproduce", "--out", " "],
                                  ["limit", "--plot", ""], ["records", ""]])
def test_an_empty_file_name_is_refused(capsys, argv):
    assert main(argv) == 2
    assert "must name a file or directory" in error_line(capsys)


# --- a '_' in a number is a typo, not digit grouping --------------------------------------------

@pytest.mark.parametrize("argv, option", [
    (["limit", "--piers", "2_5,6"], "--piers"),  # Python reads 25
    (["limit", "--piers", "3,1_2"], "--piers"),
    (["limit", "--span", "1_2", "--rise", "5", "--shape", "pointed"], "--span"),
    (["limit", "--thickness", "1_0"], "--thickness"),
    (["domain", "--amplitudes", "0.2:0_9:0.1"], "--amplitudes"),
    (["simulate", "--amplitude", "0_5"], "--amplitude"),
])
def test_number_with_an_underscore_is_refused(capsys, argv, option):
    """``float("2_5")`` is 25 to Python: a pier ten times too wide without a word. Every number
    read from text refuses a '_', naming the option (argparse's usage may come first)."""
    try:
        code = main(argv)
    except SystemExit as exc:  # an option's type is argparse's to refuse
        code = exc.code
    assert code == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert "error" in last and option in last and "_" in last


def test_description_field_with_an_underscore_is_refused():
    """The page's JSON goes to the same descriptions: a field written '1_5' is refused by name."""
    from archquake.errors import DescriptionError
    from archquake.geometry.spec import StructureSpec
    from archquake.ground_motion.spec import MotionSpec

    with pytest.raises(DescriptionError, match="piers"):
        StructureSpec.from_dict({"piers": "3_0,6"}).build()
    with pytest.raises(DescriptionError, match="thickness"):
        StructureSpec.from_dict({"thickness": "1_5"}).build()
    with pytest.raises(DescriptionError, match="amplitude"):
        MotionSpec.from_dict({"motion": "oppenheim", "amplitude": "0_4"}).build()


@pytest.mark.parametrize("command", [["simulate"], ["rigid-blocks"],
                                     ["domain", "--durations", "0.6", "--extend-to", "0"]])
@pytest.mark.parametrize("passive", ["25,0.4", "35,1"])
def test_fill_passive_is_refused_by_the_dynamic_models(command, passive, capsys):
    # the limit analysis mobilises the fill's passive reaction; neither dynamic model carries
    # it, so their activation would not be the limit analysis' k: refused, naming the option
    assert main([*command, "--fill-cover", "0.8", "--fill-passive", passive]) == 2
    err = capsys.readouterr().err
    assert err.startswith("archquake: error: --fill-passive") and "k" in err


def test_fill_passive_still_raises_k_in_the_limit_analysis(capsys):
    from archquake.geometry import StructureSpec
    from archquake.limit_analysis import both_directions

    with_passive = StructureSpec(fill_cover=0.8, fill_passive=(28.0, 0.6)).arches()[1]
    without = StructureSpec(fill_cover=0.8).arches()[1]
    assert (both_directions(with_passive)[0].load_multiplier
            > both_directions(without)[0].load_multiplier)
# --- a demanding new user -----------------------------------------------------------------------

def _filled_structure_file(tmp_path, density: float) -> Path:
    """A file of Oppenheim's arch under 0.5 m of fill, as archquake writes it (with its density)."""
    from archquake import oppenheim
    from archquake.geometry import Fill, Structure, circular_arch

    nominal = oppenheim()
    arch = circular_arch(10.0, nominal.embrace, 1.5, 7, density=density)
    path = tmp_path / f"filled_{density:g}.json"
    path.write_text(json.dumps(Structure(arch, fill=Fill(0.5, 1800.0)).to_dict()))
    return path


@settings(max_examples=5)
@given(file_density=st.sampled_from([1500.0, 2000.0, 2600.0]),
       density=st.floats(800.0, 4000.0).map(lambda x: round(x, 1)))
def test_density_option_wins_over_the_geometry_file(tmp_path_factory, file_density, density):
    """With fill, k depends on the masonry's density (the fill's weight is fixed): the k of
    ``--geometry FILE --density D`` is that of the structure built directly with D, whatever
    density the file gives; the file's own density is used without the option."""
    from archquake import oppenheim
    from archquake.geometry import Fill, Structure, circular_arch
    from archquake.limit_analysis import load_multipliers
    from fuzzing import run_cli

    path = _filled_structure_file(tmp_path_factory.mktemp("geometry"), file_density)

    def k_of(masonry):
        arch = circular_arch(10.0, oppenheim().embrace, 1.5, 7, density=masonry)
        return min(load_multipliers(Structure(arch, fill=Fill(0.5, 1800.0))))

    status, out, _ = run_cli(["limit", "--geometry", str(path), "--density", repr(density),
                              "--json"])
    assert status == 0
    assert strict_json(out)["k"] == pytest.approx(k_of(density), rel=1e-9)
    status, out, _ = run_cli(["limit", "--geometry", str(path), "--json"])
    assert strict_json(out)["k"] == pytest.approx(k_of(file_density), rel=1e-9)
    if abs(density - file_density) > 50.0:  # the option is not ignored: k moves with it
        assert abs(k_of(density) - k_of(file_density)) > 1e-4


def test_density_help_says_it_replaces_the_geometry_files(capsys):
    with pytest.raises(SystemExit):
        main(["limit", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "replaces the density of the --geometry file" in help_text


@pytest.mark.parametrize("option", ["--piers", "--pier-left", "--pier-right", "--fill-passive"])
@pytest.mark.parametrize("value", ["", " ", "\t"])
def test_an_empty_structure_option_is_refused_naming_it(capsys, option, value):
    """``--piers ""`` was a bare arch without a word (the empty text was taken as absent)."""
    assert main(["limit", "--fill-cover", "0.5", option, value]) == 2
    line = error_line(capsys)
    assert f"{option} was given an empty value" in line


@settings(max_examples=20)
@given(value=st.one_of(st.booleans(), st.floats(0.5, 20.0).map(str), st.just(None),
                       st.just(1 + 0j), st.just(b"3")),
       name=st.sampled_from(["width", "height"]))
def test_pier_refuses_booleans_and_non_numbers_naming_the_parameter(value, name):
    """``Pier(True, 6)`` was a pier 1 m wide; ``Pier("3", 6)`` one 3 m wide."""
    from archquake.geometry import Pier

    sizes = {"width": 3.0, "height": 6.0, name: value}
    with pytest.raises(ValueError, match=f"^{name} must be a number"):
        Pier(sizes["width"], sizes["height"])


@pytest.mark.parametrize("build, name", [
    (lambda g, v: g.circular_arch(v, 2.7, 1.5, 7), "radius"),
    (lambda g, v: g.circular_arch(10.0, v, 1.5, 7), "embrace"),
    (lambda g, v: g.circular_arch(10.0, 2.7, v, 7), "thickness"),
    (lambda g, v: g.shaped_arch("parabolic", span=v, rise=3.0, thickness=0.5, voussoirs=8),
     "span"),
    (lambda g, v: g.shaped_arch("parabolic", span=10.0, rise=3.0, thickness=v, voussoirs=8),
     "thickness"),
    (lambda g, v: g.Fill(v, 1800.0), "cover"),
    (lambda g, v: g.Pier.tapered(2.0, v, 6.0), "base_width"),
])
@pytest.mark.parametrize("value", [True, False, "1.5", np.bool_(True)])
def test_geometry_builders_refuse_booleans_and_text_naming_the_parameter(build, name, value):
    import archquake.geometry as geometry

    with pytest.raises(ValueError, match=f"^{name} must be a number"):
        build(geometry, value)


def test_pier_still_takes_numpy_numbers():
    from archquake.geometry import Pier

    assert Pier(np.float64(3.0), np.int64(6)) == Pier(3.0, 6.0)


@settings(max_examples=10)
@given(xtol=st.one_of(st.floats(0.010001, 1e308), st.floats(max_value=0.0),
                     st.sampled_from([math.nan, math.inf, 1e9]), st.booleans(),
                     st.just("1e-9")))
def test_min_pier_width_bounds_xtol_naming_it(nominal, xtol):
    """xtol = 1e9 returned a width on which the arch cannot stand; xtol = nan blamed the width.
    Oppenheim's arch is 10 m in size: xtol in (0, 0.01] m."""
    from archquake.limit_analysis import min_pier_width

    assert nominal.length_scale == 10.0
    with pytest.raises(ValueError, match=r"^xtol must be a number in \(0, 0.01\] m"):
        min_pier_width(nominal, 6.0, xtol=xtol)


@settings(max_examples=6)
@given(xtol=st.floats(1e-9, 1e-2), height=st.sampled_from([4.0, 6.0]))
def test_the_arch_stands_on_the_min_pier_width_for_every_xtol(nominal, xtol, height):
    """The width returned is within xtol above the root (found at 1e-12), and the arch stands on
    it: its self-weight margin is >= 0 there."""
    from archquake.geometry import Pier, Structure
    from archquake.limit_analysis import min_pier_width, self_weight_margin

    root = min_pier_width(nominal, height, xtol=1e-12)
    width = min_pier_width(nominal, height, xtol=xtol)
    assert root - 1e-12 <= width <= root + 2 * xtol + 1e-9
    pier = Pier(width, height)
    assert self_weight_margin(Structure(nominal, pier, pier)) >= 0.0


@settings(max_examples=15)
@given(radius=st.floats(1e3, 1e4), embrace=st.floats(1e-4, 0.2),
       thickness=st.sampled_from([0.01, 0.1, 1.5, 5.0]))
def test_flat_and_huge_arches_never_end_in_a_solver_traceback(radius, embrace, thickness):
    """``limit --radius 10000 --embrace 0.001``: HiGHS gave up ("Not Set") and a traceback
    followed. Every such arch now ends cleanly; one thicker than its rise, in that a horizontal
    line runs inside it from springing to springing -- the crown's intrados R - t/2 below the
    springings' extrados (R + t/2) cos(alpha/2), measured from the centre -- never collapses
    (an ever larger thrust along that line carries any load)."""
    from fuzzing import check_run, run_cli

    argv = ["limit", "--radius", repr(radius), "--embrace", repr(embrace),
            "--thickness", repr(thickness)]
    status, out, err = run_cli(argv)
    assert check_run(argv, status, out, err) in ("ok", "error")
    half = math.radians(embrace) / 2
    if radius - thickness / 2 < (radius + thickness / 2) * math.cos(half) - 1e-6:
        assert status == 2 and "does not collapse under any horizontal load" in err


def test_the_flattest_largest_arch_does_not_collapse_in_the_library():
    """The library says so too, with either method (the static one's solver gives up)."""
    from archquake.errors import NeverCollapsesError
    from archquake.geometry import circular_arch
    from archquake.limit_analysis import limit_analysis, load_multipliers

    arch = circular_arch(1e4, math.radians(1e-3), 1.5, 7)
    for method in ("static", "kinematic"):
        with pytest.raises(NeverCollapsesError):
            limit_analysis(arch, method=method)
        assert load_multipliers(arch, method) == (math.inf, math.inf)


# --- record time steps at the ends of their range --------------------------------------------

def _write_record(path, times_text):
    path.write_text("time_s,acc_g\n" + "".join(
        f"{t},{0.1 * (k % 2)}\n" for k, t in enumerate(times_text)))
    return path


@settings(max_examples=20)
@given(start=st.integers(0, 3_500_000_000), count=st.integers(2, 40))
def test_a_record_at_the_smallest_time_step_is_read(tmp_path_factory, start, count):
    """Times written to 6 decimals in steps of 1e-6 s, anywhere in the first hour: each step is
    1e-6 s up to round-off ("time step 1e-06 s ... is outside [1e-06, 1] s" was the answer)."""
    from archquake.ground_motion.records import read_record

    times = [f"{(start + k) // 10**6}.{(start + k) % 10**6:06d}" for k in range(count)]
    path = _write_record(tmp_path_factory.mktemp("rec") / "fine.csv", times)
    motion = read_record(path)
    assert motion.times[-1] == pytest.approx((start + count - 1) * 1e-6, rel=1e-12)
    assert np.diff(motion.times)[-1] == pytest.approx(1e-6, rel=1e-5)


@settings(max_examples=20)
@example(start=1, fraction=123457, count=2)
@given(start=st.integers(0, 3000), fraction=st.integers(0, 10**6 - 1),
       count=st.integers(2, 6))
def test_a_record_at_the_largest_time_step_is_read(tmp_path_factory, start, fraction, count):
    """Steps of 1 s written to 6 decimals: 2.123457 - 1.123457 = 1.0000000000000002."""
    from archquake.ground_motion.records import read_record

    assert float("2.123457") - float("1.123457") > 1.0  # the round-off this is about
    times = [f"{start + k}.{fraction:06d}" for k in range(count)]
    motion = read_record(_write_record(tmp_path_factory.mktemp("rec") / "coarse.csv", times))
    assert motion.times[-1] == pytest.approx(start + count - 1 + fraction * 1e-6, rel=1e-12)


@settings(max_examples=20)
@given(step=st.one_of(st.floats(1e-9, 0.9999e-6), st.floats(1.0001, 50.0)))
def test_a_time_step_outside_its_range_is_printed_outside_it(tmp_path_factory, step):
    """A refused step is printed with the digits that show it outside [1e-06, 1] s (never as
    one of the ends)."""
    import re

    from archquake.ground_motion.records import read_record

    path = _write_record(tmp_path_factory.mktemp("rec") / "bad.csv", ["0", repr(step)])
    with pytest.raises(ValueError, match="is outside") as caught:
        read_record(path)
    printed = float(re.search(r"the time step (\S+) s", str(caught.value)).group(1))
    assert printed < 1e-6 or printed > 1.0


# --- small ones ---------------------------------------------------------------------------------

@settings(max_examples=10)
@given(factor=st.one_of(st.integers(1001, 10**15), st.integers(-10**6, 0)))
def test_coarse_factor_is_bounded_naming_the_option(factor):
    """``--coarse-factor 20000`` was taken (and silently clipped to the longest step allowed)."""
    from fuzzing import run_cli

    status, _, err = run_cli(["rigid-blocks", "--coarse-factor", str(factor)])
    assert status == 2
    assert "--coarse-factor must be an integer in [1, 1000]" in err


@settings(max_examples=10)
@given(factor=st.integers(1, 1000))
def test_coarse_factor_within_its_range_is_taken(factor):
    from archquake.rigid_blocks import BlockSettings

    assert BlockSettings(coarse_factor=factor).coarse_factor == factor
    with pytest.raises(ValueError, match="coarse_factor must be an integer"):
        BlockSettings(coarse_factor=factor + 0.5)


@pytest.mark.parametrize("durations", ["0.5", "0.4,0.6"])
def test_domain_takes_no_progress(durations):
    """Every other command with a progress bar takes --no-progress; domain refused it."""
    from fuzzing import run_cli

    argv = ["domain", "--model", "rigid-blocks", "--durations", durations, "--amplitudes",
            "0.3:0.4:0.1", "--extend-to", "0"]
    status, _, err = run_cli([*argv, "--no-progress"])
    assert status == 0 and "%|" not in err
    status, _, err = run_cli(argv)
    assert status == 0 and "%|" in err  # the bar the option takes away


@pytest.mark.parametrize("command", [["limit"], ["simulate"], ["rigid-blocks"]])
@pytest.mark.parametrize("mobilisation", ["1.5", "-0.5", "2", "1e300"])
def test_fill_passive_error_names_fill_passive(capsys, command, mobilisation):
    """A mobilisation outside [0, 1] is --fill-passive's, not --fill-cover's."""
    assert main([*command, "--fill-cover", "0.5", "--fill-passive", f"30,{mobilisation}"]) == 2
    line = error_line(capsys)
    assert "--fill-passive" in line and "--fill-cover" not in line


@pytest.mark.parametrize("name", ["four-link", "rigid-blocks"])
@settings(max_examples=10)
@given(amplitude=st.one_of(st.floats(1.1e300, 1.7e308), st.floats(-1.7e308, -1.1e300),
                           st.just(math.nan), st.just(math.inf)))
def test_model_outcomes_name_amplitudes_g_in_g(nominal, name, amplitude):
    """``outcomes([0.4], [-1e308])`` said "amplitudes must be finite numbers [m/s^2]" after an
    overflow warning: the parameter is amplitudes_g, in g."""
    import warnings

    from archquake.models import model_for

    model = model_for(nominal, name)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow on the way
        with pytest.raises(ValueError, match=r"^amplitudes_g must be finite numbers .*\[g\]"):
            model.outcomes([0.4], [amplitude])


def test_model_outcomes_refuse_text_and_booleans_naming_the_parameter(nominal):
    from archquake.models import model_for

    model = model_for(nominal, "rigid-blocks")  # took True as 1 g
    with pytest.raises(ValueError, match="^amplitudes_g must be numbers"):
        model.outcomes([0.4], [True])
    with pytest.raises(ValueError, match="^durations must be numbers"):
        model.outcomes(["0.4"], [0.3])


@pytest.mark.parametrize("screen", ["x", 3, object()])
def test_domain_of_refuses_a_screen_that_is_not_a_model(nominal, screen):
    from archquake.models import model_for
    from archquake.studies.failure_domain import domain_of

    with pytest.raises(ValueError, match="^screen must be None or a model of a structure"):
        domain_of(model_for(nominal, "four-link"), [0.5], [0.3, 0.4], screen=screen)


@pytest.mark.parametrize("out_dir", [3, None, "", b"dir", 1.5])
def test_assess_refuses_an_out_dir_that_is_not_a_path_naming_it(out_dir):
    from archquake.report.assess import assess

    with pytest.raises(ValueError, match="^out_dir must name a directory"):
        assess(out_dir=out_dir)


def test_fragility_help_says_the_default_restitution_it_uses(capsys):
    """The help said 'nominal'; the option's default, and the study's, is 'computed'."""
    from archquake.cli import build_parser
    from archquake.cli.options import model_spec_from_args
    from archquake.defaults import DEFAULT_RESTITUTION
    from archquake.models import ModelSpec

    args = build_parser().parse_args(["fragility", "--out", "unused"])
    assert (model_spec_from_args(args).restitution == ModelSpec().restitution
            == DEFAULT_RESTITUTION == "computed")
    with pytest.raises(SystemExit):
        main(["fragility", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "Default restitution: 'computed'" in help_text
    assert "Default restitution: 'nominal'" not in help_text


@pytest.mark.parametrize("given_option, value", [("--suite", "far-field"),
                                                 ("--records", str(DATA / "decaying_sine.csv"))])
def test_record_fragility_without_levels_names_the_records_option_given(capsys, tmp_path,
                                                                       given_option, value):
    assert main(["record-fragility", given_option, value, "--out", str(tmp_path / "s"),
                 "--no-progress"]) == 2
    line = error_line(capsys)
    assert f"--levels is required with {given_option}" in line


def _survey_file(path, scale=1.0, offset=(0.0, 0.0)):
    from archquake import oppenheim

    arch = oppenheim()
    blocks = [arch.outline(i, 10)[:-1] * scale + offset for i in range(arch.n_voussoirs)]
    path.write_text(json.dumps({"blocks": [b.tolist() for b in blocks]}))
    return path


@settings(max_examples=10)
@given(exponent=st.integers(8, 307))
def test_a_survey_too_large_is_refused_for_its_coordinates_not_its_area(tmp_path_factory,
                                                                        exponent):
    """Oppenheim's arch surveyed x 1e300 was refused because it 'encloses no area' (the area
    overflowed); the error names the file and a coordinate."""
    from fuzzing import run_cli

    path = _survey_file(tmp_path_factory.mktemp("survey") / "huge.json", 10.0 ** exponent)
    status, _, err = run_cli(["limit", "--geometry", str(path)])
    assert status == 2 and "encloses no area" not in err
    assert "huge.json" in err and "too large: coordinates must be within +-1e+07 m" in err


@settings(max_examples=4)
@given(east=st.floats(0.0, 9e5), north=st.floats(0.0, 9.9e6))
def test_a_survey_in_projected_coordinates_is_analysed_as_at_the_origin(tmp_path_factory,
                                                                        east, north):
    """A translation changes no collapse multiplier: Oppenheim's arch surveyed in UTM-sized
    coordinates has the k of the same survey at the origin."""
    from archquake.geometry import load_arch
    from archquake.limit_analysis import load_multipliers

    folder = tmp_path_factory.mktemp("survey")
    here = load_multipliers(load_arch(_survey_file(folder / "here.json")))
    there = load_multipliers(load_arch(_survey_file(folder / "there.json",
                                                    offset=(east, north))))
    assert there == pytest.approx(here, rel=1e-6)


def test_assess_says_a_record_warning_once(tmp_path):
    """A record with an implausible peak (30 g) was warned of three times: twice as
    ``archquake: warning:`` (the suite read, then its intensities) and once raw, with a source
    line, by the process that runs the rigid blocks. Run as a command (that process writes to
    the same stderr)."""
    import os
    import subprocess
    import sys

    big = tmp_path / "big.csv"
    big.write_text("time_s,acc_g\n0,0\n0.01,30\n0.02,-30\n0.03,0\n0.04,0\n")
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2] / "src")}
    done = subprocess.run(
        [sys.executable, "-m", "archquake", "assess", "--records", str(big),
         str(DATA / "decaying_sine.csv"), "--quick", "--out", str(tmp_path / "report"),
         "--no-progress"], capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert lines == [line for line in lines if line.startswith("archquake: warning: ")]
    assert sum("is implausible" in line for line in lines) == 1
    assert "UserWarning" not in done.stderr


@pytest.mark.parametrize("piers", [(3.0, 6.0, 2), (2.5, 4.0, 1)])
def test_a_survey_of_a_built_structure_takes_its_time_step(piers):
    # the blocks of an arch on piers, given back as a survey: the same default time step as
    # the structure built (the survey's thickness is its median joint depth, a voussoir's)
    from archquake.geometry import StructureSpec, surveyed_arch
    from archquake.rigid_blocks.dynamics import time_step_for

    built = StructureSpec(piers=piers).arches()[1]
    survey = surveyed_arch([built.outline(i) for i in range(built.n_voussoirs)])
    assert survey.thickness_scale == pytest.approx(built.thickness_scale, rel=1e-12)
    assert time_step_for(survey) == pytest.approx(time_step_for(built), rel=1e-12)
