# The two commands of the README:
#
#   make demo   install everything into .venv, then run the supply mechanism of the theory text
#   make test   install everything into .venv, then run every test and lint
#
# Installation is done once: stamp files in .venv record what was installed, and
# the package is rebuilt only when a Rust source, a Cargo.toml or pyproject.toml
# changes. Python sources need no rebuild (maturin develop installs them in place).

SHELL := bash
.SHELLFLAGS := -euo pipefail -c
.DEFAULT_GOAL := help

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
BIN := $(abspath $(VENV))/bin
RUST_SOURCES := Cargo.toml $(wildcard Cargo.lock) $(shell find crates -name '*.rs' -o -name Cargo.toml)

.PHONY: help install demo test bench browser clean

help:
	@echo "make demo     install everything into $(VENV), then run examples/supply/supply.mec into out/supply"
	@echo "make test     install everything into $(VENV), then run the Rust and Python tests and linters"
	@echo "make bench    install everything into $(VENV), then time mechfem against its peers (benches/bench_peers.py)"
	@echo "make browser  install Debian's chromium for the report's browser test (as root; make test calls it)"
	@echo "make clean    remove $(VENV), out/ and the build products"

# A virtual environment with the build tool.
$(VENV)/.tools-stamp: pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2"
	touch $@

# The package itself (release build of the Rust module), its dependencies and the dev tools.
$(VENV)/.build-stamp: $(VENV)/.tools-stamp $(RUST_SOURCES) pyproject.toml
	VIRTUAL_ENV=$(abspath $(VENV)) PATH="$(BIN):$$PATH" $(BIN)/maturin develop --release --extras dev
	touch $@

install: $(VENV)/.build-stamp

demo: install
	$(BIN)/mechfem run examples/supply/supply.mec -o out/supply --report
	@echo "written to out/supply:"
	@ls -l out/supply

# Headless Chromium for tests/test_report_browser.py. Installed with apt-get when it is missing and we are root;
# otherwise that test is skipped and says why.
browser:
	@if command -v chromium >/dev/null 2>&1; then \
		echo "chromium: $$(command -v chromium)"; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
		echo "installing chromium (Debian package) for the report's browser test"; \
		apt-get update -qq; \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null; \
		command -v chromium; \
	else \
		echo "chromium is missing and cannot be installed here (needs root and apt-get): the browser test will be skipped"; \
	fi

test: install browser
	cargo test --workspace --exclude mechfem-py
	cargo clippy --workspace --all-targets -- -D warnings
	cargo fmt --all --check
	$(BIN)/ruff check python tests
	$(PY) -m pytest -q tests

# The peers (pylinkage with numba, mechanism) go into .venv-bench, which the script creates itself;
# mechfem is imported from this tree with the module built by `install`.
bench: install
	$(PY) benches/bench_peers.py

clean:
	rm -rf $(VENV) .venv-bench out python/mechfem/_core*.so
