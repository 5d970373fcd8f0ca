"""Every ``archquake ...`` command line that README.md and the user guide show parses with the
command line's parser (and is valid shell), the former spellings too; a few quick ones run."""

import json
import re
import shlex
import textwrap
from pathlib import Path

import pytest

from archquake.cli import attach_negative_values, build_parser, main

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
GUIDE = sorted((ROOT / "docs" / "user_guide").glob("*.rst"))


def _command_lines(lines) -> list[str]:
    """The ``archquake ...`` lines among ``lines``, continuation lines joined."""
    out, joined = [], ""
    for line in lines:
        joined += line.strip()
        if joined.endswith("\\"):
            joined = joined[:-1] + " "
            continue
        if joined.startswith("archquake ") or joined == "archquake":
            out.append(joined)
        joined = ""
    return out


def readme_commands() -> list[str]:
    """The command lines of README.md's code blocks."""
    blocks = re.findall(r"^```[^\n]*\n(.*?)^```", README.read_text(), re.DOTALL | re.MULTILINE)
    return [line for block in blocks for line in _command_lines(block.splitlines())]


def inline_commands() -> list[str]:
    """``archquake ...`` written inline in README.md and the user guide."""
    texts = [README.read_text()] + [page.read_text() for page in GUIDE]
    return [" ".join(m.split()) for text in texts
            for m in re.findall(r"(?<!`)``?(archquake [^`]+)`", text)]


def guide_commands() -> list[str]:
    """The command lines of the user guide: in its code blocks, and inline with options (one
    without options names a command: :func:`test_inline_command_names_are_commands`)."""
    out = []
    for page in GUIDE:
        for block in re.findall(r"^\.\. code-block:: (?:console|bash|shell|text)\n\n"
                                r"((?:(?:   .*)?\n)+)", page.read_text(), re.MULTILINE):
            out += _command_lines(textwrap.dedent(block).splitlines())
    return out + [line for line in inline_commands() if " -" in line]


FORMER_SPELLINGS = [
    "archquake limit --json --tolerance 0.1 --seed 7 --plot arch.png",
    "archquake limit --min-thickness --shape catenary --span 10 --rise 4.5 --voussoirs 40",
    "archquake fragility --shape elliptical --span 19.6 --rise 8 --tolerance 0.05 --out study",
    "archquake fragility --records records/ --im pga --levels 0.1:2.0:0.1 --out msa "
    "--plot-dir figs",
    "archquake fragility --records records/ --im pgv --levels 0.2:4.0:0.2 --out msa-pgv "
    "--export-nrml arch.xml --json",
    "archquake fragility --records records/ --levels 0.5:1.5:0.1 --tolerance 0 --samples 1 "
    "--out na",
    "archquake dem --amplitude -0.5 --duration 0.5 --json",
    "archquake dem --amplitude -0.6 --duration 0.3 --plot dem.png --animate dem.gif",
    "archquake mechanism --restitution blocks --json",
    "archquake simulate --tolerance 0.1 --seed 3 --restitution blocks",
]
"""Command lines of the README before the names changed (``--tolerance`` for ``--epsilon``,
``dem`` for ``rigid-blocks``, ``blocks`` for ``rigid-blocks``, ``fragility --records`` for
``record-fragility``, ``limit --min-thickness`` for ``min-thickness``): they still work."""

SHELL_PUNCTUATION = set("();<>|&")


def parse(line: str):
    """The namespace of a command line, parsed as ``archquake`` parses it (nothing run)."""
    tokens = list(shlex.shlex(line, posix=True, punctuation_chars=True))
    bad = [t for t in tokens if set(t) <= SHELL_PUNCTUATION]
    assert not bad, f"{line!r} is not one command in a shell (unquoted {bad})"
    argv = attach_negative_values(shlex.split(line, comments=True)[1:])
    name = next((a for a in argv if not a.startswith("-")), None)
    parser = build_parser(() if name is None else (name,))
    try:
        return parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version
        assert exc.code == 0, f"{line!r} does not parse"
        return None


def test_the_documents_show_command_lines():
    assert len(readme_commands()) >= 30
    assert len(guide_commands()) >= 5


def test_inline_command_names_are_commands():
    from archquake.cli import COMMANDS

    names = {alias for name, c in COMMANDS.items() for alias in (name, *c.aliases)}
    bare = [line.split()[1] for line in inline_commands() if " -" not in line]
    assert bare and set(bare) <= names


@pytest.mark.parametrize("line", readme_commands() + guide_commands() + FORMER_SPELLINGS)
def test_command_line_parses(line, capsys):
    parse(line)
    capsys.readouterr()


@pytest.mark.parametrize("former, current", [
    ("limit --tolerance 0.1 --seed 7", "limit --epsilon 0.1 --seed 7"),
    ("dem --amplitude -0.5 --duration 0.5", "rigid-blocks --amplitude -0.5 --duration 0.5"),
    ("fragility --records r/ --levels 0.5:1.5:0.1 --tolerance 0 --samples 1 --out na",
     "record-fragility --records r/ --levels 0.5:1.5:0.1 --epsilon 0 --samples 1 --out na"),
])
def test_a_former_spelling_gives_the_options_of_the_current_one(former, current, capsys):
    old, new = vars(parse("archquake " + former)), vars(parse("archquake " + current))
    capsys.readouterr()
    for name, value in new.items():
        if name != "command":
            assert old[name] == value, name


def test_quick_commands_of_the_readme_run(capsys, paper, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    lines = set(readme_commands())
    for line in ("archquake limit", "archquake mechanism --json",
                 "archquake simulate --motion ricker --amplitude -0.9 --duration 0.4"):
        assert line in {re.sub(r"\s+#.*", "", x).strip() for x in lines}, line
    assert main(["limit", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["k"] == pytest.approx(paper["table1"]["NA"]["load_multiplier"], abs=5e-3)
    assert main(["limit"]) == 0
    assert "k = min(k_l, k_r) = 0.3700" in capsys.readouterr().out
    assert main(["mechanism", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["l"]["theta_u"] == pytest.approx(paper["table2"]["NA"]["theta_u"], abs=5e-4)
    argv = shlex.split("simulate --motion ricker --amplitude -0.9 --duration 0.4 --json")
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["outcome"] in ("rest", "recovery", "collapse")
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    from archquake import __version__

    assert capsys.readouterr().out.strip() == f"archquake {__version__}"
