# lunarcap: the few verbs a newcomer needs.
#   make test   - create .venv from the hashed lock if missing/stale, check the code (ruff,
#                 the import contracts), run the test suite (unit + slow optimisation tests
#                 + papermill quick runs + a quick book in book/_build/quick)
#   make book   - create .venv likewise, execute every notebook of the manifest, build the HTML book
#                 (SCHEDULER=tcp://host:port: the book's studies on that Dask cluster)
#   make lock   - regenerate environment-lock.txt from pyproject.toml (needs network to PyPI)
#   make lint   - ruff and the import-linter contracts of pyproject.toml
#   make screenshots - built pages in headless Chromium at 1280/1024 px, offline; fails on overflow
SHELL := /bin/bash
# CPython 3.12 (the lock's; gmatpy, the GMAT engine of the tests, ships wheels for 3.12 to
# 3.15 only). PYTHON=... chooses it; otherwise the first of these that runs as 3.12:
# python3.12 on the PATH (a pyenv shim of another version does not), pyenv's newest 3.12.x
# ($$PYENV_ROOT or ~/.pyenv), /usr/local/bin and /usr/bin.
PYTHON_VERSION := 3.12
ifeq ($(origin PYTHON),undefined)
PYTHON := $(shell for p in python$(PYTHON_VERSION) \
    $$(ls -d "$${PYENV_ROOT:-$$HOME/.pyenv}"/versions/$(PYTHON_VERSION).*/bin/python$(PYTHON_VERSION) \
       2>/dev/null | sort -V -r) \
    /usr/local/bin/python$(PYTHON_VERSION) /usr/bin/python$(PYTHON_VERSION); do \
    "$$p" -c 'import sys; sys.exit("%d.%d" % sys.version_info[:2] != "$(PYTHON_VERSION)")' >/dev/null 2>&1 \
    && { echo "$$p"; break; }; done)
endif
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: test book book-quick lock lint bench clean venv screenshots chromium

venv: $(STAMP)

# uv (pinned with its hash in tools/uv-lock.txt) installs the lock: 7-12 s for what pip's
# install took 38 s, which `make book`'s 4 minutes paid before any notebook ran; pip is
# kept where uv cannot be had. Neither writes the bytecode of the ~9,400 modules of the lock
# (29 s of CPU): Python writes it on first import, for the modules used only.
$(STAMP): environment-lock.txt pyproject.toml tools/uv-lock.txt
	@[ -n "$(PYTHON)" ] || { echo "error: no CPython $(PYTHON_VERSION) found (python$(PYTHON_VERSION) on the PATH, pyenv's versions, /usr/bin); install it (e.g. pyenv install $(PYTHON_VERSION)) or set PYTHON=/path/to/python$(PYTHON_VERSION)"; exit 1; }
	@"$(PYTHON)" -c 'import sys; sys.exit("%d.%d" % sys.version_info[:2] != "$(PYTHON_VERSION)")' 2>/dev/null || { echo "error: PYTHON=$(PYTHON) is not CPython $(PYTHON_VERSION), which the lock pins"; exit 1; }
	rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	@echo "installing environment-lock.txt into $(VENV) with uv (tools/uv-lock.txt)"
	@if $(PY) -m pip install --quiet --require-hashes --no-deps -r tools/uv-lock.txt; then \
	    $(VENV)/bin/uv pip install --quiet --python $(PY) --require-hashes --no-deps -r environment-lock.txt && \
	    $(VENV)/bin/uv pip install --quiet --python $(PY) --no-deps --no-build-isolation -e .; \
	else \
	    echo "uv could not be installed: pip installs the lock instead (slower)"; \
	    $(PY) -m pip install --quiet --require-hashes --no-deps --no-compile -r environment-lock.txt && \
	    $(PY) -m pip install --quiet --no-deps --no-build-isolation -e .; \
	fi
	$(PY) -m ipykernel install --sys-prefix --name python3 >/dev/null
	touch $(STAMP)

# Debian's Chromium reads the built book as a reader does (the landing page's first screen
# in `make test`, every page in `make screenshots`); installed here when missing, as root.
CHROMIUM := $(shell command -v chromium 2>/dev/null)
chromium:
ifeq ($(CHROMIUM),)
	@if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing Debian's chromium (headless browser of the book's screenshot tests)"; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1 || \
	    { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null; }; \
	else echo "error: chromium not found; install Debian's chromium (sudo apt-get install chromium)"; exit 1; fi
endif

test: lint chromium
	$(PY) -m pytest

# SCHEDULER=tcp://host:port runs the book's studies on that existing Dask cluster (its
# workers need lunarcap importable) instead of two local worker processes.
book: $(STAMP)
	$(PY) -m lunarcap.bookbuild.build build $(if $(SCHEDULER),--scheduler $(SCHEDULER))

book-quick: $(STAMP)
	$(PY) -m lunarcap.bookbuild.build build --quick

screenshots: $(STAMP) chromium
	$(PY) -m lunarcap.bookbuild.screenshots

bench: $(STAMP)
	$(PY) -m lunarcap bench

lint: $(STAMP)
	$(VENV)/bin/ruff check lunarcap tests
	$(VENV)/bin/lint-imports

# The lock pins every package with its hashes for CPython 3.12 on Linux x86_64 (uv keeps
# the versions already in environment-lock.txt where pyproject.toml still admits them).
lock:
	$(PYTHON) -m venv .lockenv && .lockenv/bin/pip install --quiet --require-hashes -r tools/uv-lock.txt
	.lockenv/bin/uv pip compile pyproject.toml --extra test --generate-hashes \
	    --python-version $(PYTHON_VERSION) --python-platform x86_64-manylinux_2_28 \
	    --no-header -o environment-lock.txt
	rm -rf .lockenv

clean:
	rm -rf $(VENV) book/_build book/generated .cache
