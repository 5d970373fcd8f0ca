"""The interactive page: shape a structure, see its thrust line and collapse load at once, check
it against the seismic code at a site, shake it with both models and find its failure domain, in
the browser (``archquake app``).

A leaf over the library (nothing in archquake imports it), beside the command line, of which it
imports nothing. The page is plain HTML, CSS and a
little JavaScript (:file:`static/`) that draws what a small JSON API returns; the API is a
Starlette application served by uvicorn on loopback (:mod:`.server`). Its modules:

- :mod:`.inputs`: what the page sends turned into the library's values -- the structure by the
  library's description of one (:class:`archquake.geometry.StructureSpec`, which the command
  line's options map onto too, so that the page and ``archquake limit`` build the same structure
  and say the same things about bad input), the ground motion likewise
  (:class:`archquake.ground_motion.MotionSpec`), the site of the code check (its NTC 2018
  actions and knowledge level), uploaded files kept in the server's temporary folder, and the
  page's limits on sizes;
- :mod:`.views`: the library's results as the data the page draws (blocks, thrust lines,
  hinges, the code check's verdicts, tables and capacity curves, the motion of every block over
  time for both models);
- :mod:`.tasks`: the long computations (time histories of both models, failure domains, the
  assessment report), each run in a worker process of its own;
- :mod:`.jobs`: those worker processes -- started from a warm fork server, polled for progress,
  cancelled by terminating them;
- :mod:`.server`: the routes, and :func:`~archquake.app.server.serve`.

The optional dependencies are the ``app`` extra (``pip install "archquake[app]"``):
:func:`missing_dependencies` names those that are not installed.
"""

from __future__ import annotations

from importlib.util import find_spec

REQUIREMENTS = ("starlette", "uvicorn")
"""The packages of the ``app`` extra that the server imports."""


def missing_dependencies() -> list[str]:
    """The packages of :data:`REQUIREMENTS` that cannot be imported here.

    Returns
    -------
    list of str
        Empty when the page can be served.
    """
    return [name for name in REQUIREMENTS if find_spec(name) is None]


__all__ = ["REQUIREMENTS", "missing_dependencies"]
