"""Every default an option shows in ``--help`` is the library's default for the parameter it
sets: the parser's default where it has one, else the value its help states. (``fragility
--help`` once said the restitution was 'nominal' while the run used 'computed'.)"""

import dataclasses
import inspect
import math
import re

import pytest

from archquake import FourLinkModel, defaults
from archquake.cli import COMMANDS, build_parser
from archquake.defaults import DEFAULT_INTENSITY_MEASURES, REPORT_SEED
from archquake.limit_analysis import both_directions
from archquake.models import DEFAULT_MODEL, ModelSpec
from archquake.ranges import parse_values
from archquake.report.paper.settings import ReproductionSettings
from archquake.rigid_blocks import BlockSettings
from archquake.studies.comparison import compare_models
from archquake.studies.failure_domain import domain_of, inclusive_range
from archquake.studies.fragility import FragilitySettings
from archquake.studies.record_fragility import RecordFragilitySettings


def _signature_default(function, name):
    return inspect.signature(function).parameters[name].default


def _field_default(cls, name):
    field = {f.name: f for f in dataclasses.fields(cls)}[name]
    if field.default_factory is not dataclasses.MISSING:
        return field.default_factory()
    return field.default


def _domain_default(name):
    return tuple(inclusive_range(*getattr(defaults, name)).tolist())


BLOCKS = {"friction": _field_default(BlockSettings, "friction"),
          "time_step": _field_default(BlockSettings, "time_step")}
RESTITUTION = _signature_default(FourLinkModel.from_arch, "restitution")
SPEC = {option: _field_default(ModelSpec, field) for option, field in
        (("model", "name"), ("restitution", "restitution"), ("friction", "friction"),
         ("time_step", "time_step"), ("coarse_factor", "coarse_factor"))}
"""The defaults of the model options of a study: those of the spec the study takes."""

LIBRARY = {
    "limit": {"method": _signature_default(both_directions, "method")},
    "mechanism": {"restitution": RESTITUTION},
    "simulate": {"restitution": RESTITUTION},
    "rigid-blocks": BLOCKS,
    "domain": {"restitution": RESTITUTION, "model": DEFAULT_MODEL, **BLOCKS,
               "resolution": _signature_default(domain_of, "resolution_g"),
               "extend_to": _signature_default(domain_of, "extend_to_g"),
               "direction": _signature_default(domain_of, "direction"),
               "durations": _domain_default("DOMAIN_DURATIONS"),
               "amplitudes": _domain_default("DOMAIN_AMPLITUDES_G")},
    "compare": {**BLOCKS, "resolution": _signature_default(compare_models, "resolution_g"),
                "direction": _signature_default(compare_models, "direction"),
                # compare_models takes durations=None for these
                "durations": tuple(defaults.COMPARE_DURATIONS),
                "amplitudes": _domain_default("COMPARE_AMPLITUDES_G")},
    "fragility": {"samples": _field_default(FragilitySettings, "sample_size"),
                  "epsilon": _field_default(FragilitySettings, "epsilon"),
                  "seed": _field_default(FragilitySettings, "seed"),
                  **SPEC,
                  "limit_samples": _field_default(FragilitySettings, "limit_sample_size"),
                  "limit_method": _field_default(FragilitySettings, "limit_method"),
                  "durations": tuple(_field_default(FragilitySettings, "durations")),
                  "amplitudes": tuple(_field_default(FragilitySettings, "amplitudes_g"))},
    "record-fragility": {**SPEC, **{name: _field_default(RecordFragilitySettings, field)
                                    for name, field in (("samples", "sample_size"),
                                                        ("epsilon", "epsilon"), ("seed", "seed"),
                                                        ("im", "im"))}},
    "reproduce": {"seed": _field_default(ReproductionSettings, "seed")},
    "records": {"im": DEFAULT_INTENSITY_MEASURES},
}
"""For each command, the library's default of each option that sets a library parameter."""

_STATED = re.compile(r"\(default: ([^;)]+?)(?:[;)]|$)")


def _options():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    for name in COMMANDS:
        for action in sub.choices[name]._actions:
            if action.dest != "help" and action.help not in (None, "==SUPPRESS=="):
                yield name, action


def _shown(action):
    """The default as ``--help`` shows it: the parser's, else the value its help states."""
    if action.default not in (None, "==SUPPRESS==") and action.default is not False:
        return action.default
    stated = _STATED.search(" ".join(action.help.split()))
    return None if stated is None else stated.group(1).strip()


def _same(shown, library, option):
    if library is None:  # the library chooses it (the time step, from the structure)
        return str(shown).startswith("chosen from the structure")
    if isinstance(library, tuple):
        return tuple(parse_values(str(shown), option)) == pytest.approx(library, abs=1e-12)
    if isinstance(library, float | int) and not isinstance(library, bool):
        return math.isclose(float(shown), float(library), rel_tol=1e-12)
    return str(shown) == str(library)


CASES = [(name, action) for name, action in _options() if action.dest in LIBRARY.get(name, {})]


def test_the_table_covers_every_option_it_names():
    named = {(name, dest) for name, table in LIBRARY.items() for dest in table}
    found = {(name, action.dest) for name, action in CASES}
    assert named == found


@pytest.mark.parametrize("command, action", CASES,
                         ids=[f"{n}-{a.dest}" for n, a in CASES])
def test_help_default_is_the_librarys(command, action):
    shown = _shown(action)
    library = LIBRARY[command][action.dest]
    assert shown is not None, f"{command} {action.option_strings}: no default shown"
    assert _same(shown, library, action.option_strings[0]), (
        f"{command} {action.option_strings[0]}: --help shows {shown!r}, the library uses "
        f"{library!r}")


def test_the_report_seed_is_one_constant():
    assert _field_default(ReproductionSettings, "seed") == REPORT_SEED
