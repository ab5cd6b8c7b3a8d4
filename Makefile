# marm-setup: `make demo` and `make test` do all set-up on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
# Two stamps: the demo needs marm-setup and its runtime dependencies only; the test tooling (the
# `test` extra: pytest, mypy, ruff, playwright, pre-commit, ...) is installed for test/lint/fuzz/bench.
STAMP := $(VENV)/.installed-test
DEMO_STAMP := $(VENV)/.installed
DEMO_DIR ?= demo_out
DEMO_OUT := $(DEMO_DIR)/marm_moveit_config

.PHONY: demo test check lint bench fuzz clean

$(DEMO_STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet -e .
	touch $(DEMO_STAMP)

$(STAMP): pyproject.toml $(DEMO_STAMP)
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# The marm course robot: look at it, generate its MoveIt 1 package, validate it (static rules
# plus planning between its named poses, plus the real `roslaunch --dump-params` where roslaunch
# is on PATH), plan home -> forward into a trajectory file, and write the HTML report.
demo: $(DEMO_STAMP)
	$(BIN)/marm-setup inspect fixtures/marm/urdf/marm.urdf.xacro
	$(BIN)/marm-setup init fixtures/marm/urdf/marm.urdf.xacro --output $(DEMO_OUT) \
		--setup fixtures/marm/marm_setup.yaml --target ros1 --force
	$(BIN)/marm-setup validate $(DEMO_OUT)
	$(BIN)/marm-setup plan $(DEMO_OUT) --group arm --from home --to forward \
		--output $(DEMO_DIR)/home_to_forward.yaml
	$(BIN)/marm-setup report $(DEMO_OUT) --output $(DEMO_DIR)/report.html
	@echo "marm-setup is in $(BIN): '. $(BIN)/activate' puts it on PATH; open $(DEMO_DIR)/report.html"

# compileall: the `marm-setup` subprocesses the tests start then load marm_setup's bytecode
# instead of compiling every module from source (each run, under PYTHONDONTWRITEBYTECODE=1).
test: $(STAMP)
	$(BIN)/ruff check marm_setup tests benchmarks
	$(BIN)/lint-imports --no-cache
	$(BIN)/mypy
	$(BIN)/python -m compileall -q marm_setup
	$(BIN)/python -m pytest -q -p no:cacheprovider --hypothesis-profile=ci -n auto --dist loadgroup

# The inner loop: lint and the unit tests but the slow ones (the `slow` marker, tests/conftest.py),
# on every core. `make test` (and CI) runs everything.
check: $(STAMP)
	$(BIN)/ruff check marm_setup tests benchmarks
	$(BIN)/lint-imports --no-cache
	$(BIN)/python -m compileall -q marm_setup
	$(BIN)/python -m pytest -q -p no:cacheprovider --hypothesis-profile=ci -n auto --dist loadgroup -m "not slow" tests/unit

# The reliability suite at length: a random-seeded fuzzer (FUZZ_EXAMPLES per input kind) and
# RELIABILITY_KILLS SIGKILLs per writing command; prints its counts. Then the proofs' property
# tests on PROOF_EXAMPLES random robots, each proved pair checked in PROOF_STATES random states.
fuzz: $(STAMP)
	FUZZ_EXAMPLES=$${FUZZ_EXAMPLES:-300} RELIABILITY_KILLS=$${RELIABILITY_KILLS:-50} \
		$(BIN)/python -m pytest -q -s -p no:cacheprovider --hypothesis-profile=dev tests/reliability
	PROOF_STATES=$${PROOF_STATES:-1000000} PROOF_EXAMPLES=$${PROOF_EXAMPLES:-100} \
		$(BIN)/python -m pytest -q -p no:cacheprovider --hypothesis-profile=dev tests/unit/test_proof.py

lint: $(STAMP)
	$(BIN)/ruff check marm_setup tests benchmarks
	$(BIN)/lint-imports --no-cache
	$(BIN)/mypy
	$(BIN)/ruff format --check marm_setup tests benchmarks

bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[test,bench]'
	$(BIN)/python benchmarks/bench_fk.py
	$(BIN)/python benchmarks/bench_collisions.py
	$(BIN)/python benchmarks/bench_planner.py
	$(BIN)/python benchmarks/bench_validate.py
	$(BIN)/python benchmarks/bench_report.py
	$(BIN)/python benchmarks/bench_hostile.py

clean:
	rm -rf $(VENV) demo_out .pytest_cache .ruff_cache .mypy_cache .hypothesis
