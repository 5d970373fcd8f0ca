"""``archquake app`` as a user starts and stops it: the address it listens on, what it calls
this machine, and a clean stop with Ctrl-C."""

import contextlib
import io
import ipaddress
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.request

import pytest
from app_reference import ROOT
from hypothesis import given
from hypothesis import strategies as st

from archquake.app.server import is_loopback
from archquake.cli import main

STARTUP_LIMIT = 30.0
"""Seconds within which the page must be served here (about one on an idle machine)."""


def start_app(*argv):
    """``archquake app --port 0 --no-browser *argv`` in a session of its own, as a terminal
    runs it (Ctrl-C reaches the whole session): (process, url)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "PYTHONUNBUFFERED": "1"}
    process = subprocess.Popen([sys.executable, "-m", "archquake", "app", "--port", "0",
                                "--no-browser", *argv], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT,
                               start_new_session=True)
    lines = []
    reader = threading.Thread(target=lambda: lines.append(process.stdout.readline()),
                              daemon=True)
    reader.start()
    reader.join(STARTUP_LIMIT)
    match = re.search(r"(http://\S+/)", lines[0] if lines else "")
    if match is None:
        process.kill()
        raise AssertionError(f"archquake app printed no address: {lines}")
    url = match.group(1)
    deadline = time.monotonic() + STARTUP_LIMIT
    while True:
        try:
            with urllib.request.urlopen(url, timeout=2):
                return process, url
        except OSError:
            if time.monotonic() > deadline:
                process.kill()
                raise
            time.sleep(0.05)


def stop(process, sig=signal.SIGINT) -> tuple[int, str]:
    """Send ``sig`` to the app's session (Ctrl-C: SIGINT to every process of the terminal's
    group): its exit status and standard error."""
    os.killpg(process.pid, sig)
    try:
        _, err = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        raise
    return process.returncode, err


@pytest.mark.parametrize("host", ["", " ", "\t", "127.0.0.1 0.0.0.0"])
def test_empty_host_is_refused(host):
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = main(["app", "--host", host, "--no-browser", "--port", "0"])
    assert status == 2
    assert err.getvalue().startswith("archquake: error: --host must be an address to listen "
                                     "on: 127.0.0.1 (this machine only")
    assert "http://:" not in err.getvalue()


@given(address=st.ip_addresses())
def test_loopback_is_any_127_address_and_ipv6s_1(address):
    loopback = address in ipaddress.ip_network("127.0.0.0/8") or address == ipaddress.ip_address(
        "::1")
    shown = f"[{address}]" if address.version == 6 else str(address)
    assert is_loopback(shown) == is_loopback(str(address)) == loopback


@pytest.mark.parametrize("last", [2, 77])
def test_other_loopback_address_keeps_the_host_check(last):
    process, url = start_app("--host", f"127.0.0.{last}")
    try:
        assert url.startswith(f"http://127.0.0.{last}:")
        with urllib.request.urlopen(url + "api/options", timeout=10) as answer:
            assert answer.status == 200
        request = urllib.request.Request(url + "api/options",
                                         headers={"Host": "attacker.example"})
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(request, timeout=10)
        assert refused.value.code == 400
    finally:
        status, err = stop(process, signal.SIGTERM)
    assert "beyond this machine" not in err


def test_ctrl_c_after_a_job_leaves_no_leaked_semaphore():
    process, url = start_app()
    try:
        request = urllib.request.Request(
            url + "api/jobs/domain", headers={"Content-Type": "application/json"},
            data=json.dumps({"structure": {}, "domain": {"durations": "0.1:1.0:0.05"}}).encode())
        with urllib.request.urlopen(request, timeout=60) as answer:
            job = json.load(answer)
        deadline = time.monotonic() + 60
        while True:  # the job under way, its progress bar made
            with urllib.request.urlopen(f"{url}api/jobs/{job['id']}", timeout=10) as answer:
                status = json.load(answer)
            if status["progress"]["done"] >= 1:
                break
            assert status["state"] == "running" and time.monotonic() < deadline, status
            time.sleep(0.1)
    finally:
        code, err = stop(process)
    assert code == 0
    assert "leaked semaphore" not in err and "Traceback" not in err, err
