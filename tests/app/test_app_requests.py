"""The page's API refuses what a request should not carry: bodies that are not strict JSON or
hold values of the wrong kind (status 400 naming the field, never 500), requests of other web
sites, and it bounds what it keeps on disk."""

import json
import logging

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

STRUCTURE_FIELDS = ("shape", "span", "rise", "radius", "embrace", "thickness", "voussoirs",
                    "faces", "geometry", "piers", "pier_left", "pier_right", "fill_cover",
                    "fill_density", "fill_inertia", "fill_passive", "density", "epsilon", "seed")
MOTION_FIELDS = ("motion", "amplitude", "duration", "cycles", "params", "record", "suite",
                 "suite_record", "scale_to", "reverse")
SITE_FIELDS = ("ag", "f0", "tc_star", "soil", "topography", "knowledge_level", "slc_ag",
               "slc_f0", "slc_tc_star")
DOMAIN_FIELDS = ("durations", "amplitudes", "direction", "motion", "resolution", "extend_to")
MODEL_FIELDS = ("restitution", "friction")


class NoJob:
    """Stands for a started job: the properties are about the answers to the request, and a
    worker per example would only slow them."""

    def status(self, result=True):
        return {"id": "0" * 16, "state": "running"}


@pytest.fixture()
def quiet_client(client, monkeypatch):
    """The test client answering 500 for a failure of the server (rather than raising it), its
    jobs not started."""
    monkeypatch.setattr(client.app.state.jobs, "start", lambda kind, spec: NoJob())
    client.raise_server_exceptions = False
    return client


def post(client, path: str, content: bytes):
    return client.post(path, content=content, headers={"Content-Type": "application/json"})


# ------------------------------------------------------------------------ malformed bodies
scalars = (st.none() | st.booleans() | st.integers() | st.integers(min_value=10**14)
           | st.floats() | st.text(max_size=6)
           | st.sampled_from(["1.5", "0.3", "-1", "pointed", "0:1:0.1", "3_0", "1e400", "nan",
                              "l", "C", "LC2", "paper", "0123456789abcdef"]))
values = st.recursive(scalars, lambda inner: st.lists(inner, max_size=3)
                      | st.dictionaries(st.text(max_size=4), inner, max_size=3), max_leaves=6)


def fields(names):
    return st.dictionaries(st.sampled_from(names), values, max_size=4) | values


bodies = st.fixed_dictionaries({}, optional={
    "structure": fields(STRUCTURE_FIELDS), "motion": fields(MOTION_FIELDS),
    "site": fields(SITE_FIELDS), "domain": fields(DOMAIN_FIELDS),
    "models": fields(MODEL_FIELDS)})
ENDPOINTS = ("/api/structure", "/api/check", "/api/jobs/simulate", "/api/jobs/domain",
             "/api/jobs/assess")


@settings(max_examples=120, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(body=bodies, path=st.sampled_from(ENDPOINTS))
def test_any_json_body_is_answered_200_or_400_never_500(quiet_client, body, path):
    answer = post(quiet_client, path, json.dumps(body).encode())
    assert answer.status_code in (200, 400), (answer.status_code, answer.text)
    if answer.status_code == 400:
        message = answer.json()["error"]
        assert "Traceback" not in message and "sys.set_int_max_str_digits" not in message


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(depth=st.integers(min_value=17, max_value=120_000), opener=st.sampled_from("[{"),
       path=st.sampled_from(ENDPOINTS))
def test_deeply_nested_body_is_refused_with_400(quiet_client, depth, opener, path):
    content = (b'{"structure": ' + (b"[" if opener == "[" else b'{"a": ') * depth
               + b"1" + (b"]" if opener == "[" else b"}") * depth + b"}")
    answer = post(quiet_client, path, content[:250_000])
    assert answer.status_code == 400
    assert answer.json()["error"].startswith("the request is not JSON")


@pytest.mark.parametrize("digits", [4301, 4400, 60_000])
def test_integer_of_too_many_digits_is_refused_without_pythons_message(quiet_client, digits):
    answer = post(quiet_client, "/api/structure",
                  b'{"structure": {"voussoirs": ' + b"7" * digits + b"}}")
    assert answer.status_code == 400
    assert answer.json()["error"] == ("the request is not JSON the page reads: an integer of "
                                      f"{digits} digits is too long to be read")


@pytest.mark.parametrize("digits", [16, 40, 400, 4300])
@pytest.mark.parametrize("field", ["thickness", "span", "voussoirs"])
def test_huge_integer_is_refused_naming_its_field(quiet_client, field, digits):
    answer = post(quiet_client, "/api/structure",
                  f'{{"structure": {{"{field}": {"8" * digits}}}}}'.encode())
    assert answer.status_code == 400
    assert answer.json()["error"].startswith(f"{field} must be a number of this page's range; "
                                             f"got an integer of {digits} digits")


@pytest.mark.parametrize("body, key", [
    ('{"structure": {}, "structure": {"thickness": 2}}', "structure"),
    ('{"structure": {"thickness": 1.1, "thickness": 1.3}}', "thickness"),
    ('{"site": {"ag": 0.1, "f0": 2.5, "ag": 0.3}}', "ag")])
def test_duplicate_keys_are_refused(quiet_client, body, key):
    answer = post(quiet_client, "/api/check", body.encode())
    assert answer.status_code == 400
    assert answer.json()["error"].endswith(f"the key {key!r} is given twice")


@pytest.mark.parametrize("domain, field", [
    ('"y"', "domain"), ("[0.3]", "domain"), ('{"resolution": [2]}', "resolution"),
    ('{"resolution": {"a": 1}}', "resolution"), ('{"extend_to": "two"}', "extend_to"),
    ('{"extend_to": true}', "extend_to"), ('{"resolution": "3_0"}', "resolution"),
    ('{"motion": [1]}', "motion"), ('{"direction": {"l": 1}}', "direction")])
def test_domain_of_the_wrong_kind_is_refused_naming_the_field(quiet_client, domain, field):
    answer = post(quiet_client, "/api/jobs/domain",
                  f'{{"structure": {{}}, "domain": {domain}}}'.encode())
    assert answer.status_code == 400
    assert answer.json()["error"].startswith(f"{field} must be ")


def test_malformed_bodies_leave_no_traceback_in_the_log(quiet_client, caplog):
    with caplog.at_level(logging.DEBUG):
        for content in (b"[" * 100_000, b'{"structure": {"thickness": ' + b"9" * 5000 + b"}}",
                        b'{"structure": {"thickness": ' + b"9" * 400 + b"}}"):
            for path in ENDPOINTS:
                assert post(quiet_client, path, content).status_code == 400
        for content in (b'{"structure": {}, "domain": "x"}',
                        b'{"structure": {}, "domain": {"resolution": [1]}}'):
            assert post(quiet_client, "/api/jobs/domain", content).status_code == 400
    assert "Traceback" not in caplog.text


@pytest.mark.parametrize("literal", ["NaN", "Infinity", "-Infinity", "1e400", "-2.5e309"])
@pytest.mark.parametrize("field", ["thickness", "rise"])
def test_number_that_is_not_finite_is_refused_naming_its_field(quiet_client, field, literal):
    answer = post(quiet_client, "/api/structure",
                  f'{{"structure": {{"{field}": {literal}}}}}'.encode())
    assert answer.status_code == 400
    assert answer.json()["error"].startswith(f"{field} must be a finite number, got ")


# ------------------------------------------------------------------------ cross-site requests
SIMPLE_TYPES = ("text/plain", "application/x-www-form-urlencoded", "multipart/form-data",
                "text/plain;charset=UTF-8", "")
"""The body types a web site's form or script sends to another origin without asking it."""


@pytest.mark.parametrize("content_type", SIMPLE_TYPES + ("application/jsonp", "text/json"))
@pytest.mark.parametrize("path", ["/api/jobs/simulate", "/api/jobs/assess", "/api/structure"])
def test_body_not_sent_as_json_is_refused_415(quiet_client, path, content_type, monkeypatch):
    started = []
    monkeypatch.setattr(quiet_client.app.state.jobs, "start",
                        lambda kind, spec: started.append(kind) or NoJob())
    headers = {"Content-Type": content_type} if content_type else {}
    answer = quiet_client.post(path, content=b'{"structure": {}, "motion": {}}', headers=headers)
    assert answer.status_code == 415
    assert "must be sent as application/json" in answer.json()["error"]
    assert started == []
    sent = quiet_client.post(path, content=b'{"structure": {}, "motion": {}}',
                             headers={"Content-Type": "Application/JSON; charset=utf-8"})
    assert sent.status_code == 200


@pytest.mark.parametrize("content_type", SIMPLE_TYPES)
def test_upload_not_sent_as_bytes_is_refused_415(quiet_client, content_type):
    answer = quiet_client.post("/api/upload/record", content=b"0,0\n0.01,0.1\n",
                               headers={"Content-Type": content_type, "X-File-Name": "r.csv"})
    assert answer.status_code == 415
    assert list(quiet_client.app.state.workdir.glob("uploads/*")) == []


@pytest.mark.parametrize("origin", ["http://attacker.example", "http://127.0.0.1:8051",
                                    "http://localhost", "https://testserver", "null",
                                    "http://testserver.example", "http://testserver:x"])
@pytest.mark.parametrize("method, path", [("POST", "/api/jobs/simulate"),
                                          ("POST", "/api/structure"),
                                          ("DELETE", "/api/jobs/0123456789abcdef"),
                                          ("GET", "/api/options")])
def test_cross_site_request_is_refused_403(quiet_client, monkeypatch, origin, method, path):
    started = []
    monkeypatch.setattr(quiet_client.app.state.jobs, "start",
                        lambda kind, spec: started.append(kind) or NoJob())
    answer = quiet_client.request(method, path, content=b'{"structure": {}}',
                                  headers={"Content-Type": "application/json", "Origin": origin})
    assert answer.status_code == 403
    assert answer.json()["error"].startswith(f"requests from another web site ({origin})")
    assert started == []


@pytest.mark.parametrize("origin", ["http://testserver", "HTTP://TestServer",
                                    "http://testserver:80", None])
def test_same_origin_request_is_answered(quiet_client, origin):
    headers = {"Origin": origin} if origin else {}
    assert quiet_client.post("/api/structure", json={"structure": {}},
                             headers=headers).status_code == 200


@given(port=st.integers(min_value=1, max_value=65535),
       other=st.integers(min_value=1, max_value=65535),
       host=st.sampled_from(["127.0.0.1", "localhost", "[::1]", "127.0.0.2"]))
def test_same_origin_is_the_hosts_port_and_plain_http(port, other, host):
    from archquake.app.server import same_origin

    assert same_origin(f"http://{host}:{port}", f"{host}:{port}")
    assert same_origin(f"http://{host}:{other}", f"{host}:{port}") == (other == port)
    assert not same_origin(f"https://{host}:{port}", f"{host}:{port}")
    assert not same_origin(f"http://{host}.attacker.example:{port}", f"{host}:{port}")


# ------------------------------------------------------------------------ the disk the page uses
def finished_job(client, wait_seconds: float = 60.0) -> str:
    """A job that ends at once (its worker refuses the structure), started past the server's
    own checks: its id, once finished."""
    import time

    job = client.app.state.jobs.start("simulate", {"structure": {"thickness": -1}})
    deadline = time.monotonic() + wait_seconds
    while job.status(result=False)["state"] == "running":
        assert time.monotonic() < deadline
        time.sleep(0.05)
    return job.id


def write_report(folder, job_id: str) -> None:
    """The files an assessment job writes (:func:`archquake.app.tasks.assessment`)."""
    (folder / f"assessment-{job_id}").mkdir()
    (folder / f"assessment-{job_id}" / "report.html").write_text("<p>report</p>")
    (folder / f"assessment-{job_id}.zip").write_bytes(b"PK\x05\x06" + bytes(18))


@pytest.mark.parametrize("keep", [1, 2, 3])
def test_forgotten_jobs_files_are_deleted(client, keep):
    client.app.state.jobs.keep = keep
    folder = client.app.state.workdir
    ids = []
    for _ in range(keep + 2):
        ids.append(finished_job(client))
        write_report(folder, ids[-1])
    finished_job(client)  # one more is started: the finished before the last `keep` go
    kept = ids[-keep:]
    assert sorted(p.name for p in folder.glob("assessment-*")) == sorted(
        name for i in kept for name in (f"assessment-{i}", f"assessment-{i}.zip"))
    for job_id in ids:
        got = client.get(f"/api/download/assessment-{job_id}.zip")
        assert got.status_code == (200 if job_id in kept else 404)


def test_cancelled_jobs_files_are_deleted(client):
    start = client.post("/api/jobs/domain", json={
        "structure": {}, "domain": {"durations": "0.1:1.0:0.05"}}).json()
    write_report(client.app.state.workdir, start["id"])  # as a report under way would
    assert client.delete(f"/api/jobs/{start['id']}").json()["state"] == "cancelled"
    assert list(client.app.state.workdir.glob("assessment-*")) == []


def test_assessment_keeps_only_its_zip(tmp_path, monkeypatch):
    import zipfile

    from archquake.app import tasks

    def fake_report(structure, out_dir, description=None):
        (out_dir / "figures").mkdir(parents=True)
        (out_dir / "report.html").write_text("<p>report</p>")
        (out_dir / "figures" / "a.png").write_bytes(b"\x89PNG")
        return {"verdict": "v", "files": ["report.html"]}

    monkeypatch.setattr(tasks, "assessment_report", fake_report)
    out = tasks.assessment({"structure": {}, "workdir": str(tmp_path),
                            "job": "0123456789abcdef"}, lambda *a: None)
    assert [p.name for p in tmp_path.iterdir()] == [out["file"]]
    names = zipfile.ZipFile(tmp_path / out["file"]).namelist()
    assert sorted(names) == ["assessment-0123456789abcdef/figures/a.png",
                             "assessment-0123456789abcdef/report.html"]


@pytest.mark.parametrize("budget, sizes, kept", [
    (1000, [400, 400, 400], [1, 2]),     # the third pushes the first out: 800 <= 1000
    (1000, [300, 300, 300, 300], [1, 2, 3]),
    (700, [900, 100], [1]),              # the newest is kept even alone over the budget
    (10_000, [100] * 5, [0, 1, 2, 3, 4])])
def test_uploads_are_kept_within_a_byte_budget(tmp_path, budget, sizes, kept):
    from archquake.app.inputs import Uploads

    uploads = Uploads(tmp_path, keep=64, keep_bytes=budget)
    entries = [uploads.save("record", f"r{i}.csv", b"0" * size) for i, size in enumerate(sizes)]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"record-{entries[i]['token']}.csv" for i in kept)
    assert sum(p.stat().st_size for p in tmp_path.iterdir()) <= max(budget, sizes[-1])


# ------------------------------------------------------------------------ uploaded records
def triangle_record(peak_g: float) -> bytes:
    """A record in g rising linearly from 0 at 0 s to ``peak_g`` at 1 s and back to 0 at 2 s,
    sampled every 0.01 s: its peak is ``peak_g`` (the sample at 1 s)."""
    rows = [f"{k / 100:.2f},{peak_g * (1 - abs(k - 100) / 100)!r}" for k in range(201)]
    return ("time_s,acc_g\n" + "\n".join(rows) + "\n").encode()


def upload_record(client, name: str, content: bytes):
    return client.post("/api/upload/record", content=content, headers={
        "Content-Type": "application/octet-stream", "X-File-Name": name})


@settings(max_examples=12, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(peak=st.floats(min_value=10.01, max_value=999.0))
def test_uploaded_record_is_held_to_the_pages_10_g_cap(quiet_client, peak):
    from archquake.app.inputs import LIMITS

    assert LIMITS["amplitude_g"] == 10.0
    summary = upload_record(quiet_client, "strong.csv", triangle_record(peak))
    assert summary.status_code == 200
    assert summary.json()["pga_g"] == pytest.approx(peak, rel=1e-12)
    assert any("more than the 10 g this page shakes a structure with" in w
               for w in summary.json()["warnings"])
    token = summary.json()["token"]
    refused = quiet_client.post("/api/jobs/simulate", json={
        "structure": {}, "motion": {"record": token}})
    assert refused.status_code == 400
    assert refused.json()["error"].startswith(
        f"the ground motion's peak acceleration is {peak:.4g} g; this page takes at most 10 g")
    scaled = quiet_client.post("/api/jobs/simulate", json={
        "structure": {}, "motion": {"record": token, "scale_to": 0.5}})
    assert scaled.status_code == 200


@pytest.mark.parametrize("peak, warned", [(0.8, False), (4.9, False), (5.2, True),
                                          (9.9, True)])
def test_uploaded_records_unit_warning_is_in_the_answer(quiet_client, peak, warned):
    summary = upload_record(quiet_client, "in_cm.csv", triangle_record(peak)).json()
    assert summary["pga_g"] == pytest.approx(peak, rel=1e-12)
    if not warned:  # at most 5 g (PLAUSIBLE_PEAK_G) a record reads as in g
        assert summary["warnings"] == []
        return
    [warning] = summary["warnings"]
    # the library's warning, naming the file as the user did (not the server's copy)
    assert warning.startswith(f"record file 'in_cm.csv': its peak acceleration {peak:.4g} g is "
                              "implausible for a record (above 5 g)")
    # in cm/s^2 the peak is peak / 100 / 9.80665 g
    assert f"in cm/s^2 the peak is {peak / 100 / 9.80665:.3g} g" in warning


def test_simulation_under_an_implausible_record_carries_its_warning(client):
    import time

    summary = upload_record(client, "in_cm.csv", triangle_record(7.5)).json()
    start = client.post("/api/jobs/simulate", json={
        "structure": {}, "motion": {"record": summary["token"], "scale_to": 0.3}}).json()
    deadline = time.monotonic() + 120
    while (status := client.get(f"/api/jobs/{start['id']}").json())["state"] == "running":
        assert time.monotonic() < deadline
        time.sleep(0.1)
    assert status["state"] == "done", status
    [warning] = status["result"]["warnings"]
    assert warning.startswith("record file 'in_cm.csv': its peak acceleration 7.5 g")
    assert max(abs(y) for y in status["result"]["motion"]["y"]) == pytest.approx(0.3, rel=1e-9)


@settings(max_examples=80, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(content=st.binary(max_size=300) | st.text(alphabet="0123456789.,-e\n#[]{}\": ", max_size=300)
       .map(str.encode) | values.map(lambda v: json.dumps(v).encode()),
       name=st.sampled_from(["r.csv", "r.AT2", "r.asc", "g.json", "x.txt", ""]),
       kind=st.sampled_from(["record", "geometry"]))
def test_any_uploaded_file_is_answered_200_or_400_never_500(quiet_client, content, name, kind):
    answer = quiet_client.post(f"/api/upload/{kind}", content=content, headers={
        "Content-Type": "application/octet-stream", "X-File-Name": name})
    assert answer.status_code in (200, 400), (answer.status_code, answer.text)
