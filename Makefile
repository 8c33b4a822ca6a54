# The two quick-start commands: `make demo` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test test-all test-deps bench clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# setup.py builds the forward engine's compiled kernel (optional: without gcc the Python code runs)
KERNEL := setup.py $(wildcard src/nowplan/planning/_kernel*.[ch])

$(STAMP): $(BIN)/python pyproject.toml $(KERNEL)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/nowplan demo

# Test set-up beyond '.[test]': Ray for the Ray-backend test, and Debian's chromium +
# chromium-driver for the viewer's browser test (apt-get only when root and missing).
# Whatever cannot be installed, its tests skip with the reason.
TESTDEPS := $(VENV)/.test-deps

$(TESTDEPS): $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[test,test-ray]' \
	  || echo "test-deps: could not install ray; the Ray backend test will be skipped"
	touch $(TESTDEPS)

test-deps: $(TESTDEPS)
	@if [ -x /usr/bin/chromium ] && [ -x /usr/bin/chromedriver ]; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "test-deps: installing chromium and chromium-driver (apt-get)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver >/dev/null \
	    || echo "test-deps: apt-get failed; the browser test will be skipped"; \
	else echo "test-deps: chromium missing and not root; the browser test will be skipped"; fi

# the tests run in TEST_JOBS processes (pytest-xdist; the CI machine has 2 cores); TEST_JOBS=0 runs
# them in this process, e.g. `make test TEST_JOBS=0` to debug one with pdb
TEST_JOBS ?= 2

test: $(STAMP) test-deps
	$(BIN)/python -m mypy src/nowplan
	$(BIN)/python -m pytest -n $(TEST_JOBS)

test-all: $(STAMP) test-deps
	$(BIN)/python -m pytest -n $(TEST_JOBS) -m ''

bench: $(STAMP)
	$(BIN)/python benchmarks/classical.py --time-limit 10 --out benchmarks/results/classical_current
	$(BIN)/python benchmarks/logistics_hpn_fd.py --packages 8,14,20 --seeds 0,1
	$(BIN)/python benchmarks/flat_logistics.py --time-limit 30 --seeds 0,1
	rm -rf benchmarks/results/planner_profile_current && mkdir -p benchmarks/results/planner_profile_current
	for loop in python compiled; do $(BIN)/python benchmarks/planner_profile.py --regimes single,both --sizes 3,5,8 \
	  --trials 0,1 --strategies hpn --logistics 20 --flat-logistics 10,14,20 --loop $$loop --tag $$loop-1 \
	  --out benchmarks/results/planner_profile_current/planner_profile.jsonl > /dev/null; done
	$(BIN)/python benchmarks/planner_profile.py --loop-table benchmarks/results/planner_profile_current/planner_profile.jsonl \
	  > benchmarks/results/planner_profile_current/table.md
	$(BIN)/python benchmarks/summarize.py

clean:
	rm -rf $(VENV) build *.egg-info src/*.egg-info src/nowplan/planning/_kernel*.so
