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
