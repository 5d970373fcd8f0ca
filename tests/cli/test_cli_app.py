"""``archquake app``: it says how to get what it needs, refuses a port it cannot use, and its
help imports nothing heavy (tests/cli/test_cli_package.py checks every command's help)."""

import socket

import pytest

from archquake.cli import main


def test_without_the_extra_it_says_how_to_get_it(monkeypatch, capsys):
    import archquake.app

    monkeypatch.setattr(archquake.app, "missing_dependencies", lambda: ["starlette", "uvicorn"])
    assert main(["app", "--no-browser"]) == 2
    error = capsys.readouterr().err.strip()
    assert error == ('archquake: error: archquake app needs starlette, uvicorn: pip install '
                     '"archquake[app]" (or pip install starlette uvicorn)')


def test_a_port_out_of_range_is_refused(capsys):
    assert main(["app", "--port", "70000", "--no-browser"]) == 2
    assert "--port must be an integer in [0, 65535], got 70000" in capsys.readouterr().err


def test_a_port_in_use_is_refused_naming_it(capsys):
    pytest.importorskip("uvicorn", reason="the app extra is not installed")
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen(1)
        port = taken.getsockname()[1]
        assert main(["app", "--port", str(port), "--no-browser"]) == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith(f"archquake: error: --port {port}: cannot listen on 127.0.0.1: ")
