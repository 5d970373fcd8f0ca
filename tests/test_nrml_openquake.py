"""The NRML fragility models archquake writes load in OpenQuake's own reader, with the fitted
medians and dispersions recovered (OpenQuake's mean and stddev are those of the intensity in
linear space, in OpenQuake's units).

OpenQuake runs in its own interpreter (``make openquake`` builds ``.venv-openquake``; ``make
test`` passes it as ``ARCHQUAKE_OPENQUAKE_PYTHON``): the reader is called in a subprocess.
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from archquake.results_io import lognormal_moments, openquake_imt, write_fragility_nrml
from archquake.studies.fits import LognormalFragility
from archquake.studies.record_fragility import (
    RecordFragilitySettings,
    RecordSuite,
    run_record_fragility,
)

ROOT = Path(__file__).resolve().parents[1]

READER = r"""
import json, sys
import numpy as np
from openquake.hazardlib import nrml
from openquake.risklib import read_nrml  # noqa: registers the fragility model converter

out = {}
for path, imls in json.loads(sys.argv[1]).items():
    model = nrml.to_python(path)
    functions = {}
    for (imt, ident), ffl in model.items():
        ff = ffl.build(model.limitStates)[0]
        functions[ident] = {"imt": imt, "format": ffl.format, "limit_state": ff.limit_state,
                            "mean": ff.mean, "stddev": ff.stddev, "minIML": ffl.minIML,
                            "maxIML": ffl.maxIML, "poes": ff(np.array(imls)).tolist()}
    out[path] = {"limit_states": list(model.limitStates), "functions": functions}
print(json.dumps(out))
"""


def openquake_python() -> str | None:
    """An interpreter with OpenQuake's reader: $ARCHQUAKE_OPENQUAKE_PYTHON, the project's
    .venv-openquake, or this one."""
    given = os.environ.get("ARCHQUAKE_OPENQUAKE_PYTHON")
    if given:
        return given  # set by make test: it must work
    local = ROOT / ".venv-openquake" / "bin" / "python"
    if local.is_file():
        return str(local)
    try:
        import openquake.risklib  # noqa: F401
    except ImportError:
        return None
    return sys.executable


def read_with_openquake(files: dict[str, list[float]]) -> dict:
    """OpenQuake's reading of NRML files: ``{path: IMLs at which to evaluate the functions}``."""
    python = openquake_python()
    if python is None:
        pytest.skip("OpenQuake's reader is not installed: run `make openquake` (or set "
                    "ARCHQUAKE_OPENQUAKE_PYTHON)")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.run([python, "-c", READER, json.dumps(files)], capture_output=True,
                          text=True, timeout=600, env=env)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _recovered(mean, stddev):
    """Median and dispersion of a lognormal from its mean and standard deviation."""
    ratio = 1.0 + (stddev / mean) ** 2
    return mean / math.sqrt(ratio), math.sqrt(math.log(ratio))


@pytest.fixture(scope="module")
def study():
    suite = RecordSuite.from_stochastic(4, seed=0, significant_duration=4.0, midpoint_time=3.0,
                                        filter_frequency=1.0, filter_frequency_rate=0.0,
                                        duration=6.0)
    settings = RecordFragilitySettings(suite=suite, levels=(0.3, 0.6, 0.9, 1.2, 1.5, 1.8),
                                       sample_size=3, bootstrap=20)
    return run_record_fragility(settings, backend="serial", progress=False)


def test_nrml_round_trip_through_openquakes_reader(study, tmp_path):
    assert study.lognormal is not None and study.nominal_lognormal is not None
    exported = tmp_path / "study.xml"
    study.export_nrml(exported, taxonomy="masonry-arch")
    # one file per intensity measure, with a known function, for the unit conversions
    known = LognormalFragility(median=0.37, dispersion=0.42)
    others = {}
    for im in ("pgv", "pgd", "arias", "sa(0.5)"):
        path = tmp_path / f"{im.replace('(', '_').replace(')', '')}.xml"
        write_fragility_nrml(path, [("f", known.median, known.dispersion)], im=im,
                             min_iml=0.05, max_iml=3.0)
        others[im] = path
    levels = study.levels
    files = {str(exported): levels.tolist()}
    for im, path in others.items():
        files[str(path)] = (np.array([0.1, 0.37, 1.0]) * openquake_imt(im)[1]).tolist()
    read = read_with_openquake(files)

    model = read[str(exported)]
    assert model["limit_states"] == ["collapse"]
    for ident, fit in (("masonry-arch", study.lognormal),
                       ("masonry-arch-nominal", study.nominal_lognormal)):
        f = model["functions"][ident]
        assert (f["imt"], f["format"], f["limit_state"]) == ("PGA", "continuous", "collapse")
        assert (f["minIML"], f["maxIML"]) == (levels[0], levels[-1])
        median, dispersion = _recovered(f["mean"], f["stddev"])
        assert median == pytest.approx(fit.median, rel=1e-12)
        assert dispersion == pytest.approx(fit.dispersion, rel=1e-12)
        assert f["poes"] == pytest.approx(fit(levels), abs=1e-12)
    for im, path in others.items():
        imt, factor = openquake_imt(im)
        f = read[str(path)]["functions"]["f"]
        assert f["imt"] == {"sa(0.5)": "SA(0.5)"}.get(im, imt)
        median, dispersion = _recovered(f["mean"], f["stddev"])
        assert median == pytest.approx(known.median * factor, rel=1e-12)
        assert dispersion == pytest.approx(known.dispersion, rel=1e-12)
        assert f["poes"] == pytest.approx(known(np.array([0.1, 0.37, 1.0])), abs=1e-12)


def test_lognormal_moments_invert_to_median_and_dispersion():
    mean, stddev = lognormal_moments(0.8, 0.5)
    # moments of exp(N(ln 0.8, 0.5^2)), written independently
    assert mean == pytest.approx(0.8 * math.exp(0.125), rel=1e-15)
    assert stddev ** 2 == pytest.approx((math.exp(0.25) - 1) * 0.64 * math.exp(0.25), rel=1e-14)
    assert _recovered(mean, stddev) == pytest.approx((0.8, 0.5), rel=1e-14)


def test_nrml_export_refuses_what_openquake_cannot_hold(tmp_path):
    with pytest.raises(ValueError, match="no OpenQuake counterpart"):
        write_fragility_nrml(tmp_path / "x.xml", [("f", 1.0, 0.3)], im="d5-95", min_iml=1,
                             max_iml=2)
    with pytest.raises(ValueError, match="must be non-empty without"):
        write_fragility_nrml(tmp_path / "x.xml", [("a#b", 1.0, 0.3)], im="pga", min_iml=0.1,
                             max_iml=2)
    with pytest.raises(ValueError, match="median > 0 and dispersion > 0"):
        write_fragility_nrml(tmp_path / "x.xml", [("f", 1.0, 0.0)], im="pga", min_iml=0.1,
                             max_iml=2)
    assert not (tmp_path / "x.xml").exists()
