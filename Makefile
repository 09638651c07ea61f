# lunarcap: the few verbs a newcomer needs.
#   make test   - create .venv from the hashed lock if missing/stale, check the code (ruff,
#                 the import contracts), run the test suite (unit + slow optimisation tests
#                 + papermill quick runs + a quick book in book/_build/quick)
#   make book   - create .venv likewise, execute every notebook of the manifest, build the HTML book
#   make lock   - regenerate environment-lock.txt from pyproject.toml (needs network to PyPI)
#   make lint   - ruff and the import-linter contracts of pyproject.toml
#   make screenshots - built pages in headless Chromium at 1280/1024 px, offline; fails on overflow
SHELL := /bin/bash
PYTHON ?= python3.11
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: test book book-quick lock lint bench clean venv screenshots

venv: $(STAMP)

# --no-compile: the bytecode of the ~9,400 modules of the lock (29 s of CPU, in series with
# the install) is written by Python on first import instead, for the modules used only.
$(STAMP): environment-lock.txt pyproject.toml
	@command -v $(PYTHON) >/dev/null || { echo "error: $(PYTHON) not found; lunarcap needs CPython 3.11 (set PYTHON=...)"; exit 1; }
	rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --require-hashes --no-deps --no-compile -r environment-lock.txt
	$(PY) -m pip install --quiet --no-deps --no-build-isolation -e .
	$(PY) -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

test: lint
	$(PY) -m pytest

book: $(STAMP)
	$(PY) -m lunarcap.report.build build

book-quick: $(STAMP)
	$(PY) -m lunarcap.report.build build --quick

screenshots: $(STAMP)
	$(PY) -m lunarcap.report.screenshots

bench: $(STAMP)
	$(PY) -m lunarcap bench

lint: $(STAMP)
	$(VENV)/bin/ruff check lunarcap tests
	$(VENV)/bin/lint-imports

# The lock pins every package with its hashes for CPython 3.11 on Linux x86_64.
lock:
	$(PYTHON) -m venv .lockenv && .lockenv/bin/pip install --quiet "uv>=0.4"
	.lockenv/bin/uv pip compile pyproject.toml --extra test --generate-hashes \
	    --python-version 3.11 --python-platform x86_64-manylinux_2_28 \
	    --no-header -o environment-lock.txt
	rm -rf .lockenv

clean:
	rm -rf $(VENV) book/_build book/generated .cache
