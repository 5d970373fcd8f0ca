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


def test_three_spans_draw_the_bridge_its_mechanism_and_k(page):
    """Spans set to 3 on piers 3 m wide, 6 m high (two courses, the page's default, for the end
    and the middle piers): the page draws 3 x 7 voussoirs and 4 x 2 pier courses, the displaced
    blocks of the mechanism, and the k of ``archquake limit`` for the same bridge; the code
    check takes its linear route, and the parts that need one chain of voussoirs say so."""
    expected = cli_json("limit", "--spans", "3", "--piers", "3,6,2")["k"]
    page.click("details summary")
    page.check("#piers-on")
    page.fill("#pier-width", "3")
    page.fill("#pier-height", "6")
    page.fill("#spans", "3")
    page.wait_for_function(
        f"document.getElementById('k-value').textContent === '{expected:.4f}'", timeout=60_000)
    assert page.locator("#svg-l polygon.block").count() == 3 * 7 + 4 * 2
    assert page.locator("#svg-l polygon.block.pier").count() == 4 * 2
    assert page.locator("#svg-l polygon.displaced").count() > 0
    assert page.locator("#svg-l line.thrust").count() > 2 * 3 * 7
    assert page.locator("#svg-l circle.hinge").count() == 4
    assert text(page, "#assembly-first").startswith(f"At k = {expected:.4f}")
    assert "span 3 moves first" in text(page, "#assembly-first")
    assert page.locator("#assembly-laws tr").count() == 3  # the heading, +x and -x
    # the code check takes the linear route of the assembly's mechanism; the report is its own
    page.wait_for_function("document.getElementById('check-linear').textContent"
                           ".includes('toward +x')", timeout=30_000)
    assert page.locator("#check-verdict-SLV").count() == 1
    assert "not traced in its displaced configuration" in text(page, "#check-notes")
    assert page.locator("#assess").is_enabled()
    assert page.locator("#domain-start").is_enabled()  # the rigid blocks' domain alone
    assert text(page, "#domain-status") == "not computed"
    assert not page.locator("#shake-note").is_hidden()
    assert text(page, "#message") == ""
    page.fill("#spans", "1")  # back to one arch: the notes go
    page.wait_for_function("document.getElementById('shake-note').hidden === true",
                           timeout=60_000)
    assert page.locator("#svg-l polygon.displaced").count() == 0


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


# ------------------------------------------------------------------------ another web site
ATTACK = """<!doctype html><meta charset="utf-8"><title>another web site</title>
<form id="form" method="POST" enctype="text/plain" action="APP/api/jobs/assess" target="sink">
<input name='{"structure": {}, "pad": "' value='"}'></form>
<iframe name="sink"></iframe>
<script>
window.results = [];
const body = JSON.stringify({structure: {}, motion: {motion: "oppenheim", duration: 0.1}});
(async () => {
  for (const [name, init] of [
      ["text", {method: "POST", mode: "no-cors", headers: {"Content-Type": "text/plain"}, body}],
      ["form", {method: "POST", mode: "no-cors",
                headers: {"Content-Type": "application/x-www-form-urlencoded"}, body}],
      ["json", {method: "POST", headers: {"Content-Type": "application/json"}, body}]]) {
    try {
      const answer = await fetch("APP/api/jobs/simulate", init);
      window.results.push([name, answer.type]);
    } catch (error) {
      window.results.push([name, "refused by the browser"]);
    }
  }
  document.getElementById("form").submit();
})();
</script>"""
"""A page of another web site whose script makes the browser send the page's server the
requests that start jobs: as text and as a form (simple requests, sent without asking), as
JSON (which the browser sends only if the server allows it), and a form posted as text whose
body reads as JSON (``{"structure": {}, "pad": "="}``)."""


class Recorder:
    """ASGI wrapper that notes every request the application answers: method, path, headers
    and status."""

    def __init__(self, app):
        self.app = app
        self.seen = []

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        entry = {"method": scope["method"], "path": scope["path"],
                 "headers": {k.decode("latin-1").lower(): v.decode("latin-1")
                             for k, v in scope["headers"]}}
        self.seen.append(entry)

        async def noting(message):
            if message["type"] == "http.response.start":
                entry["status"] = message["status"]
            await send(message)

        await self.app(scope, receive, noting)


def serve_in_thread(app):
    """Serve an ASGI application with uvicorn on loopback in a thread: (server, url)."""
    import uvicorn

    from archquake.app.server import _listen

    sock = _listen("127.0.0.1", 0)
    server = uvicorn.Server(uvicorn.Config(app, log_level="warning", lifespan="on"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + STARTUP_LIMIT
    while not server.started:
        assert time.monotonic() < deadline and thread.is_alive()
        time.sleep(0.02)
    return server, thread, f"http://127.0.0.1:{sock.getsockname()[1]}"


def test_cross_site_post_is_refused(browser, tmp_path, monkeypatch):
    from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

    from archquake.app.server import create_app

    app = create_app(tmp_path / "work", warm=False)
    started = []
    start = app.state.jobs.start
    monkeypatch.setattr(app.state.jobs, "start",
                        lambda kind, spec: started.append(kind) or start(kind, spec))
    recorder = Recorder(app)
    server, thread, url = serve_in_thread(recorder)
    page_html = ATTACK.replace("APP", url).encode()

    class Site(BaseHTTPRequestHandler):
        def do_GET(self):
            self.send_response(200)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.end_headers()
            self.wfile.write(page_html)

        def log_message(self, *args):
            pass

    site = ThreadingHTTPServer(("127.0.0.1", 0), Site)
    threading.Thread(target=site.serve_forever, daemon=True).start()
    other = f"http://localhost:{site.server_address[1]}"  # another origin: name and port
    page = browser.new_page()
    try:
        page.goto(f"{other}/")
        page.wait_for_function("window.results.length === 3", timeout=30_000)
        deadline = time.monotonic() + 30
        while not any(e["path"] == "/api/jobs/assess" for e in recorder.seen):
            assert time.monotonic() < deadline, recorder.seen
            time.sleep(0.05)
        results = dict(page.evaluate("window.results"))
        # the control: the page itself, from the server's origin, starts a job
        page.goto(f"{url}/")
        status = page.evaluate("""async (body) => (await fetch("/api/jobs/simulate", {
            method: "POST", headers: {"Content-Type": "application/json"},
            body: JSON.stringify(body)})).status""",
                               {"structure": {}, "motion": {"motion": "oppenheim",
                                                            "duration": 0.1}})
    finally:
        page.close()
        site.shutdown()
        server.should_exit = True
        thread.join(30)
    assert status == 200 and started == ["simulate"]  # the control's job, and none other
    posts = [e for e in recorder.seen if e["method"] == "POST"
             and e["headers"].get("origin") == other]
    assert {(e["path"], e["status"]) for e in posts} == {("/api/jobs/simulate", 403),
                                                         ("/api/jobs/assess", 403)}
    assert len(posts) == 3  # text, form and the posted form; the JSON one was never sent
    assert results["json"] == "refused by the browser"  # its preflight found no permission
    assert results["text"] == results["form"] == "opaque"  # sent, the answer withheld
    assert list((tmp_path / "work").glob("assessment-*")) == []


def test_record_warning_is_shown_on_the_page(page, tmp_path):
    """A record whose peak is implausible in g (likely in cm/s^2): the library's warning is
    shown beside the file, and again over the time history it shakes."""
    peak = 6.5
    rows = [f"{k / 100:.2f},{peak * (1 - abs(k - 100) / 100)!r}" for k in range(201)]
    path = tmp_path / "in_cm.csv"
    path.write_text("time_s,acc_g\n" + "\n".join(rows) + "\n")
    page.select_option("#motion-source", "record")
    page.set_input_files("#record-file", str(path))
    page.wait_for_selector("#record-warnings:not([hidden])", timeout=30_000)
    warning = text(page, "#record-warnings")
    assert warning.startswith("Warning: record file 'in_cm.csv': its peak acceleration 6.5 g "
                              "is implausible")
    assert f"in cm/s^2 the peak is {peak / 100 / 9.80665:.3g} g" in warning
    page.fill("#scale-to", "0.2")
    page.click("#shake")
    page.wait_for_selector("#shake-warnings:not([hidden])", timeout=60_000)
    assert text(page, "#shake-warnings") == warning
