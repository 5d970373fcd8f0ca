"""Fixtures of the page's tests: the page's application in a test client."""

import pytest

pytest.importorskip("starlette", reason="the app extra (starlette, uvicorn) is not installed")


def pytest_collection_modifyitems(items):
    """Starlette's test client warns that it will move from httpx to its successor; the page's
    tests use httpx, which it still supports."""
    for item in items:
        if "tests/app/" in str(item.fspath).replace("\\", "/"):
            item.add_marker(pytest.mark.filterwarnings(
                "ignore:Using `httpx` with `starlette.testclient` is deprecated"))


@pytest.fixture(scope="session", autouse=True)
def compiled_library():
    """The compiled functions the page's workers run, compiled (or loaded from numba's cache)
    once here, before any test times a job: on a fresh clone the first compilation takes a
    minute, which no job of a test should wait for. Importing the workers' module does it
    (:func:`archquake.app.worker.warm_up`)."""
    import archquake.app.worker  # noqa: F401


@pytest.fixture()
def client(tmp_path):
    """The page's application in a test client (its jobs' workers are real processes)."""
    from starlette.testclient import TestClient

    from archquake.app.server import create_app

    app = create_app(tmp_path / "work", hosts=("testserver",), warm=False)
    with TestClient(app) as test_client:
        yield test_client
