"""The page driven in a real headless browser (Debian's Chromium through Playwright), against
``archquake app`` started as a user starts it.

Skipped, with the reason, where Playwright or Chromium is missing (``make test`` installs
Chromium with apt-get when it runs as root). Playwright never downloads a browser here: it
drives the system's Chromium by its path.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from pathlib import Path

import pytest
from app_reference import BAD_GEOMETRY, ROOT, cli_error, cli_json

sync_api = pytest.importorskip("playwright.sync_api",
                               reason="playwright is not installed (the test extra brings it)")

CHROMIUM = os.environ.get("ARCHQUAKE_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync"]
STARTUP_LIMIT = 10.0
"""Seconds within which ``archquake app`` must serve its page in this test (it takes about one
on an idle machine; the margin is for a machine shared with other work)."""

if not Path(CHROMIUM).is_file():
    pytest.skip(f"Chromium is not installed ({CHROMIUM} missing; make test installs it with "
                "apt-get as root): the page is not driven in a browser", allow_module_level=True)


def start_app():
    """``archquake app --port 0 --no-browser`` in a new process: (process, url, seconds until
    the page was served)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "PYTHONUNBUFFERED": "1"}
    start = time.monotonic()
    process = subprocess.Popen([sys.executable, "-m", "archquake", "app", "--port", "0",
                                "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, env=env, cwd=ROOT)
    lines = []
    reader = threading.Thread(target=lambda: lines.append(process.stdout.readline()),
                              daemon=True)
    reader.start()
    reader.join(STARTUP_LIMIT)
    match = re.search(r"(http://\S+/)", lines[0] if lines else "")
    if match is None:
        process.kill()
        raise AssertionError(f"archquake app printed no address: {lines} "
                             f"{process.stderr.read() if process.poll() is not None else ''}")
    url = match.group(1)
    while True:
        try:
            with urllib.request.urlopen(url, timeout=2) as response:
                assert response.status == 200
                break
        except OSError:
            if time.monotonic() - start > STARTUP_LIMIT:
                process.kill()
                raise
            time.sleep(0.05)
    return process, url, time.monotonic() - start


@pytest.fixture(scope="module")
def app_url():
    process, url, seconds = start_app()
    assert seconds < STARTUP_LIMIT
    yield url
    process.terminate()
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


@pytest.fixture(scope="module")
def browser():
    with sync_api.sync_playwright() as playwright, \
            tempfile.TemporaryDirectory(prefix="archquake-chromium-") as profile:
        context = playwright.chromium.launch_persistent_context(
            profile, executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True,
            viewport={"width": 1400, "height": 1000})
        yield context
        context.close()


@pytest.fixture()
def page(browser, app_url):
    page = browser.new_page()
    errors = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.goto(app_url)
    page.wait_for_function("document.getElementById('k-value').textContent !== '–'",
                           timeout=60_000)
    yield page
    page.close()
    assert errors == []


def text(page, selector: str) -> str:
    return page.locator(selector).inner_text().strip()


def test_thickness_changes_k_to_what_archquake_limit_prints(page):
    default = cli_json("limit")["k"]
    assert text(page, "#k-value") == f"{default:.4f}"
    for thickness in ("1.2", "0.9"):
        expected = f"{cli_json('limit', '--thickness', thickness)['k']:.4f}"
        assert expected != text(page, "#k-value")
        page.fill("#thickness", thickness)
        page.wait_for_function(
            f"document.getElementById('k-value').textContent === '{expected}'", timeout=30_000)
    assert page.locator("#svg-l .hinge").count() == 4


def test_thin_arch_cannot_stand(page):
    page.fill("#thickness", "0.3")
    page.wait_for_selector("#verdict:not([hidden])", timeout=30_000)
    assert text(page, "#verdict").startswith("Cannot stand: ")
    assert text(page, "#k-value") == "–"


def test_bad_geometry_file_gets_the_command_lines_message(page, tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(BAD_GEOMETRY)
    expected = cli_error("limit", "--geometry", "bad.json", cwd=tmp_path)
    page.check("input[name=source][value=file]")
    page.set_input_files("#geometry-file", str(path))
    page.wait_for_selector("#message:not([hidden])", timeout=30_000)
    assert text(page, "#message") == expected


def outcome_text(outcome) -> str:
    label = outcome.status.label
    if getattr(outcome, "half_cycle", 0) and label == "collapse":
        label += f" (half cycle {outcome.half_cycle})"
    return label


def test_pulse_shows_both_outcomes_and_plays_the_animation(page):
    from archquake.geometry import GRAVITY
    from archquake.ground_motion import oppenheim_pulse
    from archquake.models import model_for
    from archquake.reference_arches import oppenheim

    pulse = oppenheim_pulse(-GRAVITY, 0.44)
    expected = {name: outcome_text(model_for(oppenheim(), name, restitution="paper")
                                   .outcome(pulse))
                for name in ("four-link", "rigid-blocks")}
    page.fill("#amplitude", "-1")
    page.fill("#duration", "0.44")
    page.fill("#restitution", "paper")
    page.click("#shake")
    for name, label in expected.items():
        page.wait_for_function(
            f"document.getElementById('outcome-{name}').textContent === {label!r}",
            timeout=60_000)
    polygon = page.locator("#anim-rigid-blocks polygon.block").nth(3)
    first = polygon.get_attribute("transform")
    page.wait_for_timeout(1500)
    assert polygon.get_attribute("transform") != first  # the blocks move
    assert int(page.locator("#time").input_value()) > 0  # the clock runs


def test_failure_domain_shows_progress_can_be_cancelled_and_appears(page):
    page.fill("#domain-durations", "0.1:1.0:0.05")
    page.click("#domain-start")
    page.wait_for_function("document.getElementById('domain-progress').value >= 1",
                           timeout=60_000)
    assert re.match(r"\d+ / 38: ", text(page, "#domain-status"))
    # the page stays responsive while the domain runs
    expected = f"{cli_json('limit', '--thickness', '1.3')['k']:.4f}"
    page.fill("#thickness", "1.3")
    page.wait_for_function(
        f"document.getElementById('k-value').textContent === '{expected}'", timeout=30_000)
    page.click("#domain-cancel")
    page.wait_for_function("document.getElementById('domain-status').textContent === "
                           "'cancelled'", timeout=30_000)
    assert page.locator("#domain-start").is_enabled()
    page.fill("#domain-durations", "0.3,0.6")
    page.fill("#domain-amplitudes", "0.3:1.2:0.1")
    page.click("#domain-start")
    page.wait_for_selector("#domain-figure:not([hidden])", timeout=120_000)
    assert page.evaluate("document.getElementById('domain-figure').naturalWidth") > 500
    assert text(page, "#domain-status").startswith("done: ")


def site_verdict(ag: float) -> tuple[bool, float]:
    """Whether SLV holds for the page's default structure at the page's default site with
    ``ag``, and its PGA capacity [g], from the library directly."""
    from archquake.app.inputs import structure_from_spec
    from archquake.site.local_mechanism import SiteAction, check_local_mechanism
    from archquake.site.spectra import ntc2018_spectrum

    _, arch = structure_from_spec({})
    check = check_local_mechanism(arch, SiteAction.of("SLV", ntc2018_spectrum(ag, 2.4, 0.3, "C")),
                                  confidence_factor=1.35)
    return check.holds("SLV"), check.pga_capacity("SLV")


def test_code_check_shows_the_verdict_and_follows_the_site(page):
    for ag in (0.25, 0.8):
        holds, capacity = site_verdict(ag)
        expected = (f"SLV {'holds' if holds else 'FAILS'}: capacity/demand ",
                    f"; PGA capacity a_g = {capacity:.3f} g against the site's {ag:g} g")
        if ag != 0.25:
            page.fill("#site-ag", str(ag))
        page.wait_for_function("end => { const e = document.getElementById('check-verdict-SLV');"
                               " return e !== null && e.textContent.endsWith(end); }",
                               arg=expected[1], timeout=30_000)
        assert text(page, "#check-verdict-SLV").startswith(expected[0])
    assert not holds  # a_g = 0.8 g is beyond the capacity, about 0.7 g
    assert page.locator("#check-verdict-SLV.fails").count() == 1
    assert page.locator("#check-curve polyline").count() == 1  # Mech-l = Mech-r
    assert page.locator("#check-nonlinear td.fails").count() == 2
