"""Every ``archquake ...`` command line that README.md and the user guide show parses with the
command line's parser (and is valid shell); a few quick ones run."""

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

    bare = [line.split()[1] for line in inline_commands() if " -" not in line]
    assert bare and set(bare) <= set(COMMANDS)


@pytest.mark.parametrize("line", readme_commands() + guide_commands())
def test_command_line_parses(line, capsys):
    parse(line)
    capsys.readouterr()


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
