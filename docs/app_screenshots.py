"""Screenshots of ``archquake app`` for the user guide, taken from the running page in headless
Chromium (``make app-screenshots``).

Starts ``archquake app`` on a free port, drives the page as a user would (the default arch, a
pointed arch on piers under fill, a bridge of three spans, the code check of a thinner arch, a
pulse that collapses it, a failure domain, a refused file) and writes ``app-*.png`` into the
folder given (default ``docs/user_guide/images``).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def start_app() -> tuple[subprocess.Popen, str]:
    """``archquake app`` on a free port: its process and address."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "PYTHONUNBUFFERED": "1"}
    process = subprocess.Popen([sys.executable, "-m", "archquake", "app", "--port", "0",
                                "--no-browser"], stdout=subprocess.PIPE, text=True, env=env)
    line = process.stdout.readline()
    match = re.search(r"(http://\S+/)", line)
    if match is None:
        process.kill()
        raise SystemExit(f"archquake app printed no address: {line!r}")
    return process, match.group(1)


def wait_for(page, condition: str, timeout: float = 120.0) -> None:
    page.wait_for_function(condition, timeout=timeout * 1000)


def take(out: Path) -> list[Path]:
    """Drive the page and write the screenshots; the paths written."""
    from playwright.sync_api import sync_playwright

    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    out.mkdir(parents=True, exist_ok=True)
    written = []
    process, url = start_app()
    try:
        with sync_playwright() as playwright, tempfile.TemporaryDirectory() as profile:
            context = playwright.chromium.launch_persistent_context(
                profile, executable_path=chromium, args=ARGS, headless=True,
                viewport={"width": 1360, "height": 900}, device_scale_factor=1)
            page = context.new_page()
            page.goto(url)
            wait_for(page, "document.getElementById('k-value').textContent !== '–'")

            def shot(name: str, selector: str | None = None) -> None:
                path = out / f"app-{name}.png"
                if selector is None:
                    page.screenshot(path=str(path))
                else:
                    page.locator(selector).screenshot(path=str(path))
                written.append(path)

            # a pointed arch on piers under a fill, its thrust lines
            page.select_option("#shape", "pointed")
            page.fill("#span", "12")
            page.fill("#rise", "7")
            page.fill("#thickness", "0.8")
            page.fill("#voussoirs", "12")
            page.click("details summary")
            page.check("#piers-on")
            page.fill("#pier-width", "2.4")
            page.fill("#pier-height", "3")
            page.check("#fill-on")
            page.fill("#fill-cover", "0.6")
            page.dispatch_event("#fill-cover", "input")
            wait_for(page, "document.getElementById('description').textContent"
                           ".includes('pointed')")
            page.wait_for_timeout(500)
            shot("structure", "#structure-panel")
            # three spans of Oppenheim's arch on piers, the mechanism of each direction
            page.reload()
            wait_for(page, "document.getElementById('k-value').textContent !== '–'")
            page.click("details summary")
            page.check("#piers-on")
            page.fill("#pier-width", "3")
            page.fill("#pier-height", "6")
            page.fill("#spans", "3")
            wait_for(page, "document.getElementById('description').textContent"
                           ".includes('3 spans') && document.getElementById('assembly-first')"
                           ".textContent !== ''")
            page.wait_for_timeout(500)
            shot("spans", "#structure-panel")
            # the code check of Oppenheim's arch 1.0 m thick, at SLV and SLC
            page.reload()
            wait_for(page, "document.getElementById('k-value').textContent !== '–'")
            page.fill("#thickness", "1.0")
            page.check("#slc-on")
            wait_for(page, "document.getElementById('check-verdict-SLC') !== null && "
                           "document.getElementById('check-verdict-SLV').textContent"
                           ".includes('1.05')")
            page.wait_for_timeout(300)
            shot("check", "#check-panel")
            # back to Oppenheim's arch, shaken by the paper's pulse of Fig. 15b
            page.reload()
            wait_for(page, "document.getElementById('k-value').textContent !== '–'")
            page.fill("#amplitude", "-1")
            page.fill("#duration", "0.44")
            page.fill("#restitution", "paper")
            page.click("#shake")
            wait_for(page, "document.getElementById('outcome-rigid-blocks').textContent"
                           ".length > 2")
            page.click("#play")  # pause, and show the moment both models are well under way
            page.evaluate("""() => { const slider = document.getElementById('time');
                slider.value = Math.round(0.45 * slider.max);
                slider.dispatchEvent(new Event('input')); }""")
            page.wait_for_timeout(300)
            shot("shake", "#shake-panel")
            page.evaluate("window.scrollTo(0, 0)")
            shot("overview")
            # the failure domain of both models
            page.fill("#domain-durations", "0.1:1.0:0.1")
            page.click("#domain-start")
            wait_for(page, "document.getElementById('domain-progress').value >= 3")
            shot("domain-progress", "#domain-panel")
            page.wait_for_selector("#domain-figure:not([hidden])", timeout=300_000)
            page.wait_for_timeout(300)
            shot("domain", "#domain-panel")
            # a geometry file that is refused, with the command line's message
            bad = Path(profile) / "survey.json"
            bad.write_text('{"blocks": [[[0, 0], [1, 0], [1, 1]]]}')
            page.check("input[name=source][value=file]")
            page.set_input_files("#geometry-file", str(bad))
            page.wait_for_selector("#message:not([hidden])")
            page.evaluate("window.scrollTo(0, 0)")
            shot("refused")
            context.close()
    finally:
        process.terminate()
        process.wait(timeout=30)
    return written


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "user_guide" / "images"
    for path in take(target):
        print(path)
