"""Command-line interface: ``archquake COMMAND ...``; each command maps onto one library call.

The commands are the table :data:`COMMANDS`: a name, the module that implements it and a
one-line summary. Each module ``archquake.cli.main_<command>`` has ``configure(parser)``, which
adds the command's options (from the shared groups of :mod:`archquake.cli.options`) and imports
nothing heavy, and ``run(args) -> int``, which does the work by calling the library. A command's
module is imported only when that command runs or its ``--help`` is asked for, so ``archquake
--help``, ``archquake COMMAND --help`` and ``archquake --version`` answer without importing
numpy.

``main(argv=None)`` returns the exit status, so tests call it directly. Invalid input is reported
as ``archquake: error: ...`` with exit status 2, never as a traceback: the library's
:class:`ValueError` names its parameter, and the message names the option instead
(:func:`archquake.cli.options.option_message`). Warnings are one line ``archquake: warning:
...``. Ctrl-C (and SIGTERM during a study on worker processes) stops with ``archquake:
interrupted`` and exit status 128 + the signal number (:mod:`archquake.cli._signals`).
"""

from __future__ import annotations

import argparse
import re
import sys
import warnings
from typing import NamedTuple

from .._version import __version__
from ..errors import StudyError, interrupt_in
from . import options


class Command(NamedTuple):
    """One command of the table :data:`COMMANDS`."""

    module: str
    """Module that implements it, in :mod:`archquake.cli`: ``configure(parser)`` and
    ``run(args) -> int``."""
    summary: str
    """One line, as ``archquake --help`` lists it."""


COMMANDS = {
    "assess": Command(
        "main_assess",
        "assess a structure: limit analysis, both models under pulses, irregularity and real "
        "records, in one report (HTML, Markdown, JSON, NRML)"),
    "limit": Command(
        "main_limit",
        "limit analysis: horizontal load multipliers k_l, k_r and the collapse hinges"),
    "min-thickness": Command(
        "main_min_thickness",
        "minimum thickness under its own weight of an arch of a shape"),
    "mechanism": Command(
        "main_mechanism",
        "four-link mechanisms Mech-l and Mech-r: theta_u, links, critical angle, c_v"),
    "reproduce": Command(
        "main_reproduce",
        "regenerate every table and figure of the paper into a report (HTML, Markdown, JSON)"),
    "domain": Command(
        "main_domain",
        "failure domain of the arch over pulse duration and amplitude (Fig. 16)"),
    "fragility": Command(
        "main_fragility",
        "fragility curves and surface of irregular arches under Oppenheim's pulse "
        "(Figs. 17-21)"),
    "record-fragility": Command(
        "main_record_fragility",
        "fragility of irregular arches under a suite of records: multiple-stripe analysis"),
    "risk": Command(
        "main_risk",
        "annual frequency and probability of collapse at a site: a fragility convolved with "
        "the site's hazard curve"),
    "simulate": Command(
        "main_simulate",
        "time history of the rocking arch under a pulse, a record or a stochastic motion"),
    "records": Command(
        "main_records",
        "intensity measures (PGA, PGV, PGD, Arias, D5-95, Sa(T)) of recorded accelerograms"),
    "records-for-site": Command(
        "main_records_for_site",
        "records selected and scaled to match a site's elastic spectrum (NTC 2018 §3.2.3.6); "
        "with --run the structure under them by both models and the code's verdict"),
    "rigid-blocks": Command(
        "main_rigid_blocks",
        "rigid-block model of the arch (every voussoir a block, contacts with friction) under "
        "a pulse or a recorded accelerogram"),
    "compare": Command(
        "main_compare",
        "failure acceleration of the arch per pulse duration in the rigid-block model beside "
        "the four-link model with each restitution model"),
    "spectrum": Command(
        "main_spectrum",
        "elastic response spectrum of a site: NTC 2018, EN 1998-1, a user's table, or the NTC "
        "2018 hazard of a site at a limit state"),
    "check": Command(
        "main_check",
        "the seismic code's check of the collapse mechanism at a site (NTC 2018 §8.7.1, "
        "Circolare 2019 §C8.7.1): a0*, the capacity curve, linear and nonlinear checks, the "
        "PGA capacity"),
    "app": Command(
        "main_app",
        "interactive page in the browser: shape the structure, see its thrust line and k, "
        "shake it with both models, its failure domain (needs archquake[app])"),
}
"""The commands: name -> :class:`Command`, in the order ``archquake --help`` lists them."""

DESCRIPTION = ("Seismic response of masonry arches with geometrical irregularities: limit "
               "analysis, four-link rocking dynamics with impacts, failure domains and "
               "fragility. Units: m, s, rad; angles on the command line in degrees and "
               "accelerations in g where stated.")


def command_module(name: str):
    """The module of command ``name``, imported."""
    from importlib import import_module

    return import_module(f"{__name__}.{COMMANDS[name].module}")


def build_parser(commands=None) -> argparse.ArgumentParser:
    """The option parser of ``archquake``.

    Parameters
    ----------
    commands : iterable of str, optional
        The commands whose options are built (importing their modules); the others are listed
        with their summaries only. Default: every command.

    Returns
    -------
    argparse.ArgumentParser
    """
    wanted = set(COMMANDS) if commands is None else set(commands)
    parser = argparse.ArgumentParser(prog="archquake", description=DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"archquake {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name, command in COMMANDS.items():
        subparser = sub.add_parser(name, help=command.summary, description=command.summary)
        if name in wanted:
            command_module(name).configure(subparser)
    return parser


_NEGATIVE_VALUE = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


def attach_negative_values(argv: list[str]) -> list[str]:
    """``--option -1e-3`` as ``--option=-1e-3``: argparse takes a value that starts with a dash
    and is not a plain number (``-1e-3``, ``-1:1:0.5``, ``-inf``) for an option of its own."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        if (argv[i].startswith("--") and "=" not in argv[i] and i + 1 < len(argv)
                and _NEGATIVE_VALUE.match(argv[i + 1])):
            out.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


def _command_name(argv: list[str]) -> str | None:
    """The command of ``argv``: its first word that is not an option (``archquake`` itself has
    no option that takes a value)."""
    return next((a for a in argv if not a.startswith("-")), None)


def main(argv: list[str] | None = None) -> int:
    """Run ``archquake`` with the arguments ``argv`` (default ``sys.argv[1:]``).

    Parameters
    ----------
    argv : list of str, optional
        The arguments, without the program name.

    Returns
    -------
    int
        The exit status: 0, 2 for invalid input (one line on stderr), 128 + the signal number
        when interrupted. ``--help``, ``--version`` and a command line that does not parse exit
        through :class:`SystemExit`, as argparse does.
    """
    argv = attach_negative_values(sys.argv[1:] if argv is None else list(argv))
    name = _command_name(argv)
    parser = build_parser(() if name is None else (name,))
    args = parser.parse_args(argv)
    args.argv = list(argv)  # the command line, for a command that records it
    from ..compiled import enable_notes

    enable_notes()  # a first run that compiles an engine says so (archquake.compiled)
    return run_command(command_module(args.command), args)


def run_command(module, args: argparse.Namespace) -> int:
    """Run ``module.run(args)``: errors, warnings (each message once) and interrupts as one line
    on stderr, and the exit status."""
    from ._signals import interrupted, sigterm_as_interrupt

    shown: set[str] = set()

    def show_once(message, category, filename, lineno, file=None, line=None) -> None:
        # a record read again later in the run (its intensities, a study) warns again
        if str(message) not in shown:
            shown.add(str(message))
            _show_warning(message, category, filename, lineno, file, line)

    show_warning, warnings.showwarning = warnings.showwarning, show_once
    try:
        if "workers" in vars(args):  # one check of --workers for every command
            args.workers = options.check_workers(args.workers)
        options.check_paths(args)  # and of every file or directory name
        # a study on worker processes (or a command that starts one of its own, as the
        # report does): SIGTERM stops it like Ctrl-C, which terminates them
        with sigterm_as_interrupt(getattr(args, "workers", None) is not None
                                  or getattr(module, "STARTS_PROCESSES", False)):
            return int(module.run(args) or 0)
    except KeyboardInterrupt as exc:  # Ctrl-C or SIGTERM: stop without a traceback
        return interrupted(exc, args)
    except (ValueError, StudyError, SystemError) as exc:
        # Ctrl-C inside a compiled call surfaces as a SystemError caused by the interrupt
        interrupt = interrupt_in(exc)
        if interrupt is not None:
            return interrupted(interrupt, args)
        if isinstance(exc, SystemError):
            raise
        print(f"archquake: error: {options.option_message(str(exc))}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file or directory given on the command line cannot be used
        where = f": {exc.filename!r}" if exc.filename else ""
        print(f"archquake: error: {exc.strerror or exc}{where}", file=sys.stderr)
        return 2
    finally:
        warnings.showwarning = show_warning


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning on the command line: one line, like the errors."""
    print(f"archquake: warning: {message}", file=sys.stderr if file is None else file)


__all__ = ["COMMANDS", "Command", "build_parser", "main"]
