# The two commands of the README:
#
#   make demo   install everything into .venv, then run the supply mechanism of the theory text
#   make test   install everything into .venv, then run every test and lint
#
# Installation is done once: stamp files in .venv record what was installed, and
# the package is rebuilt only when a Rust source, a Cargo.toml, .cargo/config.toml or pyproject.toml
# changes. Python sources need no rebuild (maturin develop installs them in place).

SHELL := bash
.SHELLFLAGS := -euo pipefail -c
.DEFAULT_GOAL := help

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
BIN := $(abspath $(VENV))/bin
RUST_SOURCES := Cargo.toml $(wildcard Cargo.lock) .cargo/config.toml $(shell find crates -name '*.rs' -o -name Cargo.toml)

.PHONY: help install demo test bench browser docs fuzz fuzz-seeds clean

help:
	@echo "make demo     install everything into $(VENV), then run examples/supply/supply.mec into out/supply"
	@echo "make test     install everything into $(VENV), then run the Rust and Python tests and linters"
	@echo "make bench    install everything into $(VENV), then time mechfem against its peers (benches/bench_peers.py)"
	@echo "make browser  install Debian's chromium for the report's browser test (as root; make test calls it)"
	@echo "make docs     install everything into $(VENV), then build the documentation site into site/ (mkdocs, --strict)"
	@echo "make fuzz     fuzz the deck reader and the run for FUZZ_SECONDS (default $(FUZZ_SECONDS)) per target (nightly Rust, cargo-fuzz)"
	@echo "make clean    remove $(VENV), out/ and the build products"

# A virtual environment with the build tool.
$(VENV)/.tools-stamp: pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2"
	touch $@

# The package itself (the Rust module built with the Cargo profile BUILD_PROFILE), its dependencies and
# the dev tools. The stamp holds the profile it was built with. `make test` asks for the quick profile
# (Cargo.toml: optimised like release, without whole-program LTO, several minutes less to build) and
# accepts a release build already there; demo and bench ask for release and rebuild a quick one.
BUILD_PROFILE ?= release
STAMP := $(VENV)/.build-stamp

# The stamp takes the time the build started, so that a source edited while it ran is newer than the stamp
# and the next `make install` builds again.
$(STAMP): $(VENV)/.tools-stamp $(RUST_SOURCES) pyproject.toml
	touch $@.started
	VIRTUAL_ENV=$(abspath $(VENV)) PATH="$(BIN):$$PATH" $(BIN)/maturin develop --profile $(BUILD_PROFILE) --extras dev
	echo $(BUILD_PROFILE) > $@
	touch -r $@.started $@ && rm -f $@.started

install:
	@built="$$(cat $(STAMP) 2>/dev/null || true)"; \
	if [ -n "$$built" ] && [ "$$built" != "$(BUILD_PROFILE)" ] && [ "$$built" != release ]; then rm -f $(STAMP); fi; \
	if [ -f $(STAMP) ] && [ -z "$$built" ]; then rm -f $(STAMP); fi
	@$(MAKE) --no-print-directory $(STAMP) BUILD_PROFILE=$(BUILD_PROFILE)

demo: install
	$(BIN)/mechfem run examples/supply/supply.mec -o out/supply --report
	@echo "written to out/supply:"
	@ls -l out/supply

# Headless Chromium for tests/report/test_report_browser.py. Installed with apt-get when it is missing and we are root;
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

# Chromium is installed (network and disk) while clippy checks the crates and pip installs the package's dependencies
# (mostly network and disk) before maturin builds it: clippy's target/debug and the build's target/quick are separate
# build directories, so cargo runs the two side by side. Clippy's report is shown when the package is installed. The
# Rust steps build without incremental caches unless CARGO_INCREMENTAL says otherwise: `make test` mostly runs on a
# fresh clone, where a cache is written and never read. mypy (one process) checks the Python package while rustdoc
# and the Rust tests build, so that the second core is not idle. pytest's summary gives the time of the slow families
# (browser, cluster, large_run: pyproject.toml) apart from the rest.
test: BUILD_PROFILE = quick
test: export CARGO_INCREMENTAL ?= 0
test:
	mkdir -p target
	cargo clippy --workspace --all-targets -- -D warnings > target/clippy.log 2>&1 & clippy=$$!; \
	$(MAKE) --no-print-directory browser & browser=$$!; \
	$(MAKE) --no-print-directory install BUILD_PROFILE=quick; \
	wait $$browser; \
	wait $$clippy || { cat target/clippy.log; exit 1; }; cat target/clippy.log
	cargo fmt --all --check
	$(BIN)/ruff check python tests
	$(BIN)/mypy --strict python/mechfem > .venv/mypy.log 2>&1 & mypy=$$!; \
	RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps && cargo test --workspace --exclude mechfem-py \
		|| { wait $$mypy; exit 1; }; \
	wait $$mypy || { cat .venv/mypy.log; exit 1; }; cat .venv/mypy.log
	$(PY) -m pytest -q -n auto tests

# The documentation site: docs/*.md with mkdocs (a dev dependency) into site/; --strict fails on any warning,
# a broken link among them (mkdocs.yml, scripts/mkdocs_hooks.py).
docs: install
	$(PY) -m mkdocs build --strict --site-dir site
	@echo "open site/index.html in a web browser"

# The peers (pylinkage with numba, mechanism) go into .venv-bench, which the script creates itself;
# mechfem is imported from this tree with the module built by `install`.
bench: install
	$(PY) benches/bench_peers.py

# Fuzzing with cargo-fuzz (docs/robustness.md): nightly Rust and cargo-fuzz are installed when
# missing. Not part of `make test`: CI has no nightly. Each target starts from the seeds (the
# repository's decks, among them every input that once failed) and keeps what it finds in
# fuzz/corpus/<target>; a failing input is written to fuzz/artifacts/<target>.
FUZZ_SECONDS ?= 60
FUZZ_TIMEOUT ?= 10
FUZZ_TARGETS := deck_parse deck_run deck_grammar
SEED_DECKS := $(wildcard examples/*/*.mec tests/decks/*.mec crates/mechfem-deck/tests/decks/*/*.mec)

# fuzz/seeds holds a copy of every deck of the repository, named after its path.
fuzz-seeds:
	mkdir -p fuzz/seeds
	@for d in $(SEED_DECKS); do cp "$$d" "fuzz/seeds/$$(echo "$$d" | sed 's#^crates/mechfem-deck/tests/decks/#deck_#; s#^tests/decks/#run_#; s#/#_#g')"; done

fuzz: fuzz-seeds
	rustup toolchain list | grep -q '^nightly' || rustup toolchain install nightly --profile minimal
	cargo fuzz --version >/dev/null 2>&1 || cargo install cargo-fuzz
	for t in $(FUZZ_TARGETS); do \
		mkdir -p fuzz/corpus/$$t; \
		cp fuzz/seeds/* fuzz/corpus/$$t/; \
		(cd fuzz && cargo +nightly fuzz run $$t -- -max_total_time=$(FUZZ_SECONDS) -timeout=$(FUZZ_TIMEOUT) -dict=deck.dict); \
	done

clean:
	rm -rf $(VENV) .venv-bench out site python/mechfem/_core*.so
