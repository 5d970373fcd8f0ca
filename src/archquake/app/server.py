"""The page's server: a Starlette application (:func:`create_app`) served by uvicorn
(:func:`serve`).

Routes (JSON in and out unless said otherwise; a refused input is answered with status 400 and
``{"error": message}``, the library's message for the same input, which names the field where
the command line names the option):

- ``GET /``: the page; ``GET /static/...``: its script and style sheet;
- ``GET /api/options``: the choices the page offers (shapes, faces, motions and their
  parameters, the defaults and the page's limits); ``GET /api/suites``: the built-in record
  suites and their records when the ``records`` extra is installed (read once, seconds);
- ``POST /api/structure``: ``{"structure": {...}}`` -> the blocks, both limit analyses (k_l,
  k_r, hinges, thrust lines) or why the structure cannot stand; answered in the server's threads
  (a limit analysis takes milliseconds);
- ``POST /api/figure``: the same structure -> a PNG of both mechanisms
  (:func:`archquake.plotting.plot_limit_analysis`);
- ``POST /api/check``: ``{"structure": {...}, "site": {...}}`` -> the seismic code check of the
  structure's collapse mechanism at the site (NTC 2018 §8.7.1, Circolare 2019 §C8.7.1), or why
  the structure cannot stand; answered in the server's threads (a tenth of a second for an
  arch of a few voussoirs);
- ``POST /api/upload/geometry``, ``POST /api/upload/record``: the file as the request body, its
  name in the header ``X-File-Name`` -> a token, once the file has been read as the command line
  reads it;
- ``POST /api/jobs/simulate``, ``/api/jobs/domain``, ``/api/jobs/assess``: start a job
  (:mod:`.jobs`) -> its id; ``GET /api/jobs/{id}``: its progress and, once done, its result;
  ``DELETE /api/jobs/{id}``: cancel it;
- ``GET /api/download/{name}``: a file a job wrote (the assessment report, zipped).

The server writes only in its temporary folder (uploads, reports), removed when it stops, and
reads no request body larger than its limits. What it keeps there is bounded: the last
:data:`~archquake.app.inputs.LIMITS` ``["uploads"]`` uploads within ``["uploads_bytes"]``, and
the files of the jobs it keeps (:data:`~archquake.app.jobs.KEEP_FINISHED`): a job's report is
deleted when the job is forgotten or cancelled, and no longer offered for download.

A web site open in the same browser could otherwise make the browser send requests to the page
(a form's or a script's request to any address is sent, only its answer is withheld), and so
start jobs. The server refuses them three ways: it answers only requests whose ``Host`` is the
address it serves (a site's own name resolved to this machine, "DNS rebinding", is refused:
status 400); it refuses a request whose ``Origin`` header, which browsers send with every
request but a plain navigation, names another origin (status 403, :class:`SameOrigin`); and it
reads a body only when it is declared as JSON (``application/json``) or, for an upload, as
bytes (``application/octet-stream``), types that a browser sends to another origin only after
asking it, which the server never allows (status 415). A program's request, which carries no
``Origin``, is answered: the server is as open to the programs of this machine's users as any
local port (``--host`` other than loopback opens it to the network, with no authentication).
"""

from __future__ import annotations

import asyncio
import io
import json
import math
import os
import re
import shutil
import socket
import sys
import tempfile
import threading
import webbrowser
from contextlib import asynccontextmanager
from pathlib import Path

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import FileResponse, HTMLResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from .inputs import LIMITS

STATIC = Path(__file__).parent / "static"
"""The page's files."""

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "::1", "[::1]")
"""Host names that a server on loopback answers."""

_DOWNLOAD = re.compile(r"^assessment-([0-9a-f]{16})\.zip$")


class RequestError(Exception):
    """A request the server refuses: its status and message."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


def _error(status: int, message: str) -> JSONResponse:
    return JSONResponse({"error": message}, status_code=status)


async def _body(request: Request, limit: int) -> bytes:
    """The request's body, refused past ``limit`` bytes without reading the rest."""
    length = request.headers.get("content-length")
    if length is not None and length.isdigit() and int(length) > limit:
        raise RequestError(413, f"the request has {int(length)} bytes; this page takes at most "
                                f"{limit}")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise RequestError(413, f"the request has more than {limit} bytes; this page takes "
                                    f"at most {limit}")
        chunks.append(chunk)
    return b"".join(chunks)


def _require_type(request: Request, media_type: str) -> None:
    """Refuse a body not declared as ``media_type`` (status 415): a web site can make the
    user's browser send a form's or a script's body as text or a form (a "simple" request, sent
    without asking the server first) to any address, but not as JSON or as bytes."""
    given = request.headers.get("content-type", "").split(";", 1)[0].strip().lower()
    if given != media_type:
        raise RequestError(415, f"the request's body must be sent as {media_type}, got "
                                f"{given or 'no Content-Type'}")


async def _json(request: Request) -> dict:
    _require_type(request, "application/json")
    data = await _body(request, LIMITS["request_bytes"])
    return read_request(data)


def read_request(data: bytes) -> dict:
    """The JSON object of a request's body, read strictly (:func:`archquake.checks.json_loads`:
    a key given twice, a nesting too deep are refused), with nothing the page cannot
    take (:func:`check_values`).

    Raises
    ------
    RequestError
        Status 400, saying what is wrong (and where: the field of a number out of range).
    """
    from ..checks import json_loads

    try:
        # NaN read, to be refused naming its field (check_values)
        value = json_loads(data.decode("utf-8"), allow_nan=True)
    except UnicodeDecodeError as exc:
        raise RequestError(400, f"the request is not JSON: not UTF-8 text (byte {exc.start})"
                           ) from None
    except json.JSONDecodeError as exc:
        raise RequestError(400, f"the request is not JSON: {exc.msg} (line {exc.lineno}, "
                                f"column {exc.colno})") from None
    except ValueError as exc:  # a key given twice, nested too deeply, digits too many
        raise RequestError(400, f"the request is not JSON the page reads: {exc}") from None
    if not isinstance(value, dict):
        raise RequestError(400, "the request must be a JSON object")
    check_values(value)
    return value


MAX_INTEGER_DIGITS = 15
"""Most digits of an integer in a request: more is no size, count or seed of the page (and an
integer beyond a float's range cannot even be compared with one)."""

MAX_NESTING = 16
"""Most levels of objects and lists in a request (the page's own nest three: the request, the
motion, its parameters)."""


def check_values(value) -> None:
    """Refuse a request nested more than :data:`MAX_NESTING` levels deep, with a number that is
    not finite (``NaN``, ``1e400``) or an integer of more than :data:`MAX_INTEGER_DIGITS`
    digits, naming its field (the innermost key; ``[i]`` for the i-th item of a list).

    Raises
    ------
    RequestError
        Status 400.
    """
    stack = [(value, "the request", 0)]
    while stack:
        item, name, depth = stack.pop()
        if isinstance(item, (dict, list)) and depth >= MAX_NESTING:
            raise RequestError(400, f"the request is not JSON the page reads: it nests objects "
                                    f"and lists more than {MAX_NESTING} levels deep")
        if isinstance(item, dict):
            stack.extend((v, str(k), depth + 1) for k, v in item.items())
        elif isinstance(item, list):
            stack.extend((v, f"{name}[{i}]", depth + 1) for i, v in enumerate(item))
        elif isinstance(item, float) and not math.isfinite(item):
            raise RequestError(400, f"{name} must be a finite number, got {item!r}")
        elif (isinstance(item, int) and not isinstance(item, bool)
              and abs(item) >= 10**MAX_INTEGER_DIGITS):
            raise RequestError(400, f"{name} must be a number of this page's range; got an "
                                    f"integer of {len(str(abs(item)))} digits (at most "
                                    f"{MAX_INTEGER_DIGITS})")


def _handler(function):
    """An endpoint whose refusals are answers: a :class:`ValueError` is status 400 with the
    library's message (the field named), a :class:`RequestError` its own status."""

    async def endpoint(request: Request):
        try:
            return await function(request)
        except RequestError as exc:
            return _error(exc.status, str(exc))
        except ValueError as exc:
            return _error(400, str(exc))

    endpoint.__name__ = function.__name__
    endpoint.__doc__ = function.__doc__
    return endpoint


class SameOrigin:
    """ASGI middleware: refuse (status 403) a request that a page of another origin made the
    user's browser send.

    A browser names the page that made a request in its ``Origin`` header on every request but
    a plain navigation or a same-origin ``GET``; the request is refused when that origin is not
    the server's own (``http://`` and the ``Host`` the request was sent to, which
    :class:`~starlette.middleware.trustedhost.TrustedHostMiddleware` has checked), or is
    ``null`` (a sandboxed frame, a local file). A request without ``Origin`` -- a program's, as
    ``curl``'s or the tests' -- is not a browser's on behalf of a web site and is answered.
    """

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] == "http":
            headers = {k.decode("latin-1").lower(): v.decode("latin-1")
                       for k, v in scope["headers"]}
            origin = headers.get("origin")
            if origin is not None and not same_origin(origin, headers.get("host", "")):
                response = _error(403, f"requests from another web site ({origin}) are refused: "
                                       "open the page itself")
                await response(scope, receive, send)
                return
        await self.app(scope, receive, send)


def same_origin(origin: str, host: str) -> bool:
    """Whether the ``Origin`` of a request is the server's own: ``http://`` and its ``Host``
    (names compared without case, a missing port as 80).

    Examples
    --------
    >>> same_origin("http://127.0.0.1:8050", "127.0.0.1:8050")
    True
    >>> same_origin("http://127.0.0.1:8000", "127.0.0.1:8050")
    False
    """
    match = re.fullmatch(r"http://([^/?#@\s]+)", origin.strip(), flags=re.IGNORECASE)
    if match is None:
        return False
    return _netloc(match.group(1)) == _netloc(host)


def _netloc(text: str) -> str:
    """``host:port`` without case, the port 80 left out as a browser leaves it out."""
    text = text.strip().lower()
    return text[:-3] if text.endswith(":80") else text


# ------------------------------------------------------------------------------ computations
def structure_answer(spec: dict) -> dict:
    """What the page shows of a structure: its blocks and both limit analyses.

    Parameters
    ----------
    spec : dict
        The structure's description (:func:`archquake.app.inputs.structure_from_spec`, files
        resolved).

    Returns
    -------
    dict
        ``structure`` (:func:`~archquake.app.views.structure_view`), and ``limit``
        (:func:`~archquake.app.views.limit_view`) or, when the structure cannot stand or never
        collapses, ``verdict`` (``"cannot stand"`` or ``"never collapses"``) and ``message``
        (the library's, which names the part). A block assembly (several spans or rings) is
        analysed as ``archquake limit`` analyses it
        (:func:`archquake.limit_analysis.assembly_limits`, both directions, both friction
        laws when an interface can slide; ``limit`` is then
        :func:`~archquake.app.views.assembly_limit_view`), and ``unavailable`` says which
        parts of the page need one chain of voussoirs, and why
        (:data:`~archquake.app.inputs.ASSEMBLY_UNAVAILABLE`).
    """
    from ..errors import CannotStandError, NeverCollapsesError
    from ..limit_analysis import assembly_limits, both_directions
    from .inputs import ASSEMBLY_UNAVAILABLE, is_assembly, structure_from_spec
    from .views import assembly_limit_view, json_ready, limit_view, structure_view

    _, structure = structure_from_spec(spec)
    out = {"structure": structure_view(structure), "limit": None}
    if is_assembly(structure):
        out["unavailable"] = ASSEMBLY_UNAVAILABLE
    try:
        if is_assembly(structure):
            out["limit"] = assembly_limit_view(structure, assembly_limits(structure))
        else:
            out["limit"] = limit_view(both_directions(structure))
    except CannotStandError as exc:
        out.update(verdict="cannot stand", message=str(exc))
    except NeverCollapsesError as exc:
        out.update(verdict="never collapses", message=str(exc))
    return json_ready(out)


def check_answer(spec: dict, site: dict) -> dict:
    """What the page shows of the code check of a structure at a site ("Is it safe here?").

    Parameters
    ----------
    spec : dict
        The structure's description (as :func:`structure_answer` takes it).
    site : dict
        The site's description (:func:`archquake.app.inputs.site_from_spec`).

    Returns
    -------
    dict
        ``description`` of the structure, ``confidence_factor`` [-], and ``check``
        (:func:`~archquake.app.views.check_view`) or, when the structure cannot stand, never
        collapses or has no mechanism the check can take, ``verdict`` (``"cannot stand"``,
        ``"never collapses"`` or ``"not checked"``) and ``message`` (the library's). A block
        assembly (several spans or rings) has the linear route alone (its note says why).

    Raises
    ------
    ValueError
        For a bad site or structure, naming the field (the site is read first).
    """
    from ..errors import CannotStandError, NeverCollapsesError
    from ..geometry.structure import describe_arch
    from ..limit_analysis import both_directions
    from ..site.local_mechanism import check_local_mechanism
    from .inputs import is_assembly, site_from_spec, structure_from_spec
    from .views import check_view, describe_assembly, json_ready

    actions, fc = site_from_spec(site)
    _, structure = structure_from_spec(spec)
    assembly = is_assembly(structure)
    out = {"description": describe_assembly(structure) if assembly else describe_arch(structure),
           "confidence_factor": fc, "check": None}
    try:
        limit = None if assembly else both_directions(structure)
        check = check_local_mechanism(structure, actions, confidence_factor=fc, limit=limit)
    except CannotStandError as exc:
        out.update(verdict="cannot stand", message=str(exc))
    except NeverCollapsesError as exc:
        out.update(verdict="never collapses", message=str(exc))
    except ValueError as exc:  # the site was read above: this is the structure's mechanism
        out.update(verdict="not checked", message=str(exc))
    else:
        out["check"] = check_view(check)
    return json_ready(out)


def limit_figure(spec: dict) -> bytes:
    """PNG of both mechanisms of the structure (:func:`archquake.plotting.plot_limit_analysis`,
    or :func:`archquake.plotting.plot_assembly_limit` for a block assembly, every friction
    law's, as ``archquake limit --plot`` draws them)."""
    from ..limit_analysis import assembly_limits, both_directions
    from .inputs import is_assembly, structure_from_spec
    from .views import pyplot

    plt = pyplot()
    from ..plotting import plot_assembly_limits, plot_limit_analysis

    _, structure = structure_from_spec(spec)
    if is_assembly(structure):
        return _png(plt, plot_assembly_limits(assembly_limits(structure)))
    results = both_directions(structure)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.0), constrained_layout=True)
    for ax, result in zip(axes, results, strict=True):
        plot_limit_analysis(result, ax)
    return _png(plt, fig)


def _png(plt, fig) -> bytes:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110)
    plt.close(fig)
    return buffer.getvalue()


def options_answer() -> dict:
    """The choices the page offers, its defaults and limits."""
    from ..defaults import (
        ANALYTIC_GROUND_MOTIONS,
        DEFAULT_FILL_INERTIA,
        DEFAULT_FRICTION,
        DEFAULT_PULSE,
        DEFAULT_RESTITUTION,
        FILL_INERTIA_MODELS,
        SHAPES,
        VOUSSOIR_FACES,
        circular_defaults,
    )
    from ..ground_motion import shape_parameters
    from .tasks import DOMAIN_DEFAULTS

    return {"shapes": list(SHAPES), "faces": list(VOUSSOIR_FACES),
            "fill_inertia": list(FILL_INERTIA_MODELS), "default_fill_inertia":
                DEFAULT_FILL_INERTIA,
            "circular": circular_defaults(),
            "motions": {name: shape_parameters(name) for name in ANALYTIC_GROUND_MOTIONS},
            "pulse": {"amplitude": DEFAULT_PULSE[0], "duration": DEFAULT_PULSE[1]},
            "restitution": DEFAULT_RESTITUTION, "friction": DEFAULT_FRICTION,
            "domain": DOMAIN_DEFAULTS, "limits": LIMITS}


# ------------------------------------------------------------------------------ the application
def create_app(workdir: str | Path | None = None, *, hosts=LOOPBACK_NAMES,
               warm: bool = True) -> Starlette:
    """The page's application.

    Parameters
    ----------
    workdir : str or Path, optional
        The folder the server writes in (uploads, reports); default a new temporary folder,
        removed when the application stops (a given folder is left in place).
    hosts : sequence of str
        Host names the server answers (``"*"``: any); default loopback's.
    warm : bool
        Start the fork server of the jobs and import the limit analysis when the application
        starts, in the background (the page is served meanwhile).

    Returns
    -------
    starlette.applications.Starlette
    """
    from .inputs import Uploads, check_geometry_file, check_record_file
    from .jobs import BusyError, Jobs
    from .tasks import TASKS, check_domain, model_settings

    own = workdir is None
    folder = Path(tempfile.mkdtemp(prefix="archquake-app-") if own else workdir)
    uploads = Uploads(folder / "uploads")
    jobs = Jobs(forget=lambda job_id: delete_job_files(folder, job_id))
    suite_list: list = []
    suite_lock = threading.Lock()

    def read_suites() -> list:
        from .inputs import suites

        with suite_lock:
            if not suite_list:
                suite_list.append(suites())
            return suite_list[0]

    @asynccontextmanager
    async def lifespan(app):
        warm_up = threading.Thread(target=_warm_up, args=(read_suites,),
                                   name="archquake-app-warm-up", daemon=True)
        if warm:
            warm_up.start()
        try:
            yield
        finally:
            if warm_up.is_alive():
                # a thread left inside the record files' HDF5 library at exit holds its lock,
                # and the interpreter's finalisation then waits on it for ever (Ctrl-C during
                # the warm-up): the reading ends first
                await run_in_threadpool(warm_up.join, WARM_UP_TIMEOUT)
            await run_in_threadpool(jobs.shutdown)
            if own:
                shutil.rmtree(folder, ignore_errors=True)

    async def page(request: Request):
        return HTMLResponse((STATIC / "index.html").read_text(encoding="utf-8"))

    async def options(request: Request):
        return JSONResponse(await run_in_threadpool(options_answer))

    async def suite_names(request: Request):
        return JSONResponse(await run_in_threadpool(read_suites))

    async def structure(request: Request):
        spec = uploads.resolve((await _json(request)).get("structure") or {}, "geometry",
                               "geometry")
        return JSONResponse(await run_in_threadpool(structure_answer, spec))

    async def figure(request: Request):
        spec = uploads.resolve((await _json(request)).get("structure") or {}, "geometry",
                               "geometry")
        png = await run_in_threadpool(limit_figure, spec)
        return Response(png, media_type="image/png")

    async def check(request: Request):
        body = await _json(request)
        spec = uploads.resolve(body.get("structure") or {}, "geometry", "geometry")
        return JSONResponse(await run_in_threadpool(check_answer, spec, body.get("site")))

    async def upload(request: Request):
        kind = request.path_params["kind"]
        if kind not in uploads.KINDS:
            raise RequestError(404, f"no upload of kind {kind!r}")
        _require_type(request, "application/octet-stream")
        data = await _body(request, LIMITS[f"{kind}_bytes"])
        entry = uploads.save(kind, request.headers.get("x-file-name", ""), data)
        check = check_geometry_file if kind == "geometry" else check_record_file
        try:
            summary = await run_in_threadpool(check, entry)
        except ValueError:
            uploads.forget(entry["token"])
            raise
        out = {"token": entry["token"], "name": entry["name"]}
        if kind == "record":
            out.update(summary)
        return JSONResponse(out)

    def _job_spec(body: dict) -> dict:
        spec = {key: body.get(key) for key in ("structure", "motion", "models", "domain")
                if body.get(key) is not None}
        spec["structure"] = uploads.resolve(spec.get("structure") or {}, "geometry",
                                            "geometry")
        if "motion" in spec:
            spec["motion"] = uploads.resolve(spec["motion"], "record", "record")
        spec["workdir"] = str(folder)
        return spec

    def _check(kind: str, spec: dict) -> None:
        """Refuse bad input before a worker is started (the worker checks it again)."""
        from .inputs import motion_from_spec, structure_from_spec

        structure_from_spec(spec["structure"])
        model_settings(spec)
        if kind == "simulate":
            motion_from_spec(spec.get("motion") or {})
        if kind == "domain":
            check_domain(spec)

    async def start_job(request: Request):
        kind = request.path_params["kind"]
        if kind not in TASKS:
            raise RequestError(404, f"no job of kind {kind!r}; kinds: {list(TASKS)}")
        spec = _job_spec(await _json(request))
        await run_in_threadpool(_check, kind, spec)
        try:
            job = await run_in_threadpool(jobs.start, kind, spec)
        except BusyError as exc:
            raise RequestError(429, str(exc)) from None
        return JSONResponse(job.status(result=False))

    def _job(request: Request):
        try:
            return jobs.get(request.path_params["job"])
        except KeyError:
            raise RequestError(404, "no such job (or no longer kept)") from None

    async def job_status(request: Request):
        job = _job(request)
        return JSONResponse(await run_in_threadpool(job.status))

    async def job_cancel(request: Request):
        job = _job(request)
        await run_in_threadpool(job.cancel)
        if job.state == "cancelled":  # what it wrote before it was ended is of no use
            await run_in_threadpool(delete_job_files, folder, job.id)
        return JSONResponse(job.status(result=False))

    async def download(request: Request):
        name = request.path_params["name"]
        path = folder / name
        match = _DOWNLOAD.match(name)
        if not match or not path.is_file():
            raise RequestError(404, "no such file")
        try:
            jobs.get(match.group(1))
        except KeyError:  # its job is forgotten: its files are being deleted
            raise RequestError(404, "no such file (its job is no longer kept)") from None
        return FileResponse(path, media_type="application/zip", filename=name)

    routes = [
        Route("/", page),
        Route("/api/options", _handler(options)),
        Route("/api/suites", _handler(suite_names)),
        Route("/api/structure", _handler(structure), methods=["POST"]),
        Route("/api/figure", _handler(figure), methods=["POST"]),
        Route("/api/check", _handler(check), methods=["POST"]),
        Route("/api/upload/{kind}", _handler(upload), methods=["POST"]),
        Route("/api/jobs/{kind}", _handler(start_job), methods=["POST"]),
        Route("/api/jobs/{job}", _handler(job_status), methods=["GET"]),
        Route("/api/jobs/{job}", _handler(job_cancel), methods=["DELETE"]),
        Route("/api/download/{name}", _handler(download)),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    middleware = [Middleware(TrustedHostMiddleware, allowed_hosts=list(hosts)),
                  Middleware(SameOrigin)]
    app = Starlette(routes=routes, middleware=middleware, lifespan=lifespan)
    app.state.workdir = folder
    app.state.jobs = jobs
    app.state.uploads = uploads
    return app


def delete_job_files(folder: Path, job_id: str) -> None:
    """Delete what the job ``job_id`` wrote in the server's folder (its assessment report, the
    zip and the folder it was made in), once the job is forgotten or cancelled."""
    (folder / f"assessment-{job_id}.zip").unlink(missing_ok=True)
    shutil.rmtree(folder / f"assessment-{job_id}", ignore_errors=True)


WARM_UP_TIMEOUT = 120.0
"""Longest wait for the warm-up (the fork server, the limit analysis's import, the record
suites' names) to end when the server stops [s]."""


def _warm_up(read_suites) -> None:
    """Start the jobs' fork server, import the limit analysis and read the names of the
    built-in record suites (in the background)."""
    from .jobs import start_fork_server

    try:
        start_fork_server()
        structure_answer({"voussoirs": 4})
        read_suites()
    except Exception as exc:  # the page works without: the first request then waits
        print(f"archquake app: warning: warm-up failed: {exc}", file=sys.stderr)


def _listen(host: str, port: int) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host.strip("[]"), port))
    except OSError as exc:
        sock.close()
        raise ValueError(f"--port {port}: cannot listen on {host}: "
                         f"{exc.strerror or exc}") from None
    sock.listen(128)
    return sock


def check_host(host: str) -> str:
    """The address ``--host`` names, checked: a name or an IP address, not empty (an empty
    address listens on every interface, which is no default to fall into by mistake).

    Raises
    ------
    ValueError
        Naming ``--host``.
    """
    text = host.strip() if isinstance(host, str) else ""
    if not text or any(c.isspace() for c in text) or "/" in text:
        raise ValueError(f"--host must be an address to listen on: 127.0.0.1 (this machine only, "
                         f"the default), or e.g. 0.0.0.0 to serve every network interface; got "
                         f"{host!r}")
    return text


def is_loopback(host: str) -> bool:
    """Whether ``host`` is this machine only: ``localhost``, any of 127.0.0.0/8 or ``::1``.

    Examples
    --------
    >>> [is_loopback(h) for h in ("127.0.0.2", "[::1]", "localhost", "0.0.0.0", "10.0.0.1")]
    [True, True, True, False, False]
    """
    import ipaddress

    name = host.strip().strip("[]").lower()
    if name == "localhost":
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:  # another name: it may resolve anywhere
        return False


def serve(host: str = "127.0.0.1", port: int = 8050, *, open_browser: bool = True,
          log=None) -> int:
    """Serve the page until interrupted (Ctrl-C or SIGTERM).

    Parameters
    ----------
    host : str
        Address to listen on (default loopback only).
    port : int
        TCP port; 0 picks a free one.
    open_browser : bool
        Open the page in the user's browser (when there is a display); the address is printed
        on standard output in any case.
    log : file, optional
        Where the server's warnings go (default standard error).

    Returns
    -------
    int
        0 once stopped.

    Raises
    ------
    ValueError
        If the address is empty (:func:`check_host`) or cannot be listened on (the port in
        use, an unknown host).
    """
    import uvicorn

    host = check_host(host)
    sock = _listen(host, port)
    shown = host if ":" not in host else f"[{host.strip('[]')}]"
    url = f"http://{shown}:{sock.getsockname()[1]}/"
    loopback = is_loopback(host)
    hosts = (*LOOPBACK_NAMES, host.strip("[]").lower(), shown.lower()) if loopback else ("*",)
    app = create_app(hosts=hosts)
    config = uvicorn.Config(app, log_level="warning", lifespan="on", timeout_graceful_shutdown=5)
    server = uvicorn.Server(config)
    print(f"archquake app: serving on {url} (Ctrl-C stops)", flush=True)
    if not loopback:
        print("archquake app: warning: the page is served beyond this machine, with no "
              "authentication", file=log or sys.stderr, flush=True)
    if open_browser:
        if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY")
                                                     or os.environ.get("WAYLAND_DISPLAY")):
            print("archquake app: no display to open a browser on: open the address above",
                  flush=True)
        else:
            threading.Timer(0.3, webbrowser.open, [url]).start()
    try:
        asyncio.run(server.serve(sockets=[sock]))
    except KeyboardInterrupt:
        pass
    finally:
        sock.close()
    return 0


__all__ = ["LOOPBACK_NAMES", "RequestError", "SameOrigin", "check_answer", "check_host",
           "create_app", "delete_job_files", "is_loopback", "limit_figure", "options_answer",
           "read_request", "same_origin", "serve", "structure_answer"]
