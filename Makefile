# The two commands: `make run` and `make test`. Both create .venv on first use; `make run`
# installs only what the package needs, `make test` adds the test tools, `make docs` the
# documentation tools.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
BASE := $(VENV)/.installed-base
TEST := $(VENV)/.installed-test
DOCS := $(VENV)/.installed-docs
DOC_OUTPUTS := docs/_build docs/api/generated docs/auto_examples docs/sg_execution_times.rst

OQ_VENV := .venv-openquake
OQ := $(OQ_VENV)/.installed

.PHONY: run test fuzz docs lint bench clean openquake chromium app-screenshots

# pip --no-compile, then the byte code written on both processors and without the
# dependencies' own test suites (which nothing here imports): 19 s instead of 31 s for the
# package's install. The byte code matters even where Python would write it on first import:
# under PYTHONDONTWRITEBYTECODE every process would compile scipy, numba and pandas again.
BYTE_CODE = $(BIN)/python -m compileall -q -j 0 -x '/tests?/' $(VENV)/lib > /dev/null

# The package's own byte code, brought up to date before a run (a fraction of a second when it
# is): under PYTHONDONTWRITEBYTECODE every process, each worker included, would otherwise
# compile archquake's modules from source at import, 0.5 s a process.
SRC_BYTE_CODE = $(BIN)/python -m compileall -q src > /dev/null

$(BASE): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --no-compile -e .
	$(BYTE_CODE)
	touch $@

# The records extra (the FEMA P695 record sets, about 300 MB with its dependencies) so that
# the tests of the built-in suites run.
$(TEST): $(BASE)
	$(BIN)/pip install --quiet --no-compile -e ".[test,records]"
	$(BYTE_CODE)
	touch $@

# The API pages import every module, archquake.app (the app extra) included: `make docs` on a
# fresh clone installs both extras. The stamp depends on this file so that a .venv made by an
# older recipe is brought up to date.
$(DOCS): $(BASE) Makefile
	$(BIN)/pip install --quiet --no-compile -e ".[docs,app]"
	$(BYTE_CODE)
	touch $@

# OpenQuake's reader, which a test uses to load the NRML fragility models archquake writes, in a
# venv of its own (its pins and size stay out of .venv): the `openquake` extra of pyproject.toml.
# The last command imports the reader once, writing its byte code (about a minute).
$(OQ): pyproject.toml
	$(PYTHON) -m venv $(OQ_VENV)
	$(OQ_VENV)/bin/pip install --quiet $$($(PYTHON) -c "import tomllib; print(' '.join(tomllib.load(open('pyproject.toml', 'rb'))['project']['optional-dependencies']['openquake']))")
	$(OQ_VENV)/bin/python -c "from openquake.hazardlib import nrml; from openquake.risklib import read_nrml"
	touch $@

openquake: $(OQ)

# Chromium, in which the page's tests (tests/app/test_app_browser.py) drive `archquake app`:
# Debian's package, installed when missing if this runs as root with apt-get (as CI does).
# Where it cannot be installed, make goes on and those tests are skipped with the reason.
chromium:
	@if command -v chromium >/dev/null 2>&1; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
		echo "installing Chromium (apt-get) for the browser tests of archquake app"; \
		{ apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
			apt-get install -y -qq chromium >/dev/null; } \
		|| echo "Chromium could not be installed: the browser tests will be skipped"; \
	else \
		echo "Chromium is missing and cannot be installed here (apt-get as root): the browser" \
			"tests will be skipped"; \
	fi

run: $(BASE)
	$(SRC_BYTE_CODE)
	$(BIN)/archquake reproduce --out report

test: $(TEST) $(OQ) chromium
	$(SRC_BYTE_CODE)
	ARCHQUAKE_OPENQUAKE_PYTHON=$(CURDIR)/$(OQ_VENV)/bin/python $(BIN)/python -m pytest -q

# The property-based fuzzers (tests marked fuzz) with Hypothesis's "fuzz" profile: hundreds of
# examples per property where `make test` runs twenty (tests/conftest.py).
fuzz: $(TEST)
	HYPOTHESIS_PROFILE=fuzz $(BIN)/python -m pytest -q -m fuzz --hypothesis-show-statistics

# The site in docs/_build/html, built from scratch (every example runs) and offline; a warning
# fails the build.
docs: $(DOCS)
	rm -rf $(DOC_OUTPUTS)
	$(BIN)/python -m sphinx -b html -n -W --keep-going docs docs/_build/html

# The screenshots of the user guide's page on archquake app, taken from the running app in
# headless Chromium (docs/user_guide/images/app-*.png).
app-screenshots: $(TEST) chromium
	$(BIN)/python docs/app_screenshots.py docs/user_guide/images

lint: $(TEST)
	$(BIN)/ruff check src tests benchmarks examples docs

bench: $(TEST)
	$(BIN)/python benchmarks/run_all.py

clean:
	rm -rf $(VENV) $(OQ_VENV) build dist src/*.egg-info .pytest_cache $(DOC_OUTPUTS)
