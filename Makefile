# Thin wrapper over CMake. `make demo` and `make test` install what is missing first.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX     ?= /usr/local
VALGRIND    = valgrind --quiet --error-exitcode=1 --leak-check=full \
              --errors-for-leak-kinds=definite,indirect --show-possibly-lost=no \
              --suppressions=tests/valgrind.supp \
              --trace-children=yes \
              --trace-children-skip=/bin/*,/usr/bin/*

.PHONY: all deps build install demo test test-unit asan-build test-asan memcheck bench format \
        clean fuzz fuzz-build fuzz-smoke python test-python help

all: build ## the same as build

# `make help` (and `./setup help`): the targets, from the `## ` line after each one's name
help: ## this list
	@echo "Makefile targets (make TARGET, or ./setup TARGET on a fresh machine):"
	@sed -n 's/^\([a-z-]*\):.*## \(.*\)/  \1\t\2/p' $(MAKEFILE_LIST) | expand -t 18

deps: ## install what is missing (apt-get, npm ci)
	@bash scripts/install-deps.sh
	@# plotly.js (inlined into HTML plots, installed with the library) and playwright-core
	@# (the browser tests), pinned by package-lock.json; again only when the lock changed
	@[ node_modules/.package-lock.json -nt package-lock.json ] || npm ci --no-audit --no-fund --loglevel=error

build: deps ## configure and build into $(BUILD) (Release)
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

# The libraries, the CLI, the headers, geardyn.pc and the CMake package under PREFIX.
install: build ## install under PREFIX (default /usr/local)
	cmake --install $(BUILD) --prefix $(PREFIX)

demo: build python ## build, then run the demo on examples/rig2018.yaml
	./$(BUILD)/geardyn check examples/rig2018.yaml
	@echo
	./$(BUILD)/geardyn modal examples/rig2018.yaml --speed 3000rpm --modes 12
	@echo
	PYTHONPATH=python $(PYTHON) python/examples/kumar_tables.py --table-only
	@echo
	@./$(BUILD)/geardyn report examples/rig2018.yaml --out $(BUILD)/rig2018_report.html >/dev/null
	@echo "report (open it in a browser, it works offline): $(CURDIR)/$(BUILD)/rig2018_report.html"

# The Python package (python/, docs/python.md): the cffi extension module over
# $(BUILD)/libgeardyn.so, built with Debian's Python (no download).
PYTHON ?= /usr/bin/python3
python: build ## the Python package (cffi over libgeardyn.so)
	@$(PYTHON) python/build_ffi.py --libdir $(BUILD)

test-python: python ## the Python tests (pytest)
	cd python && OPENBLAS_NUM_THREADS=1 GEARDYN_BUILD=../$(BUILD) $(PYTHON) -m pytest -q -p no:cacheprovider tests

# Every test: the normal build, then AddressSanitizer + UndefinedBehaviorSanitizer,
# then valgrind on the normal build, the fuzz smoke run and the Python tests.
test: test-unit test-asan memcheck fuzz-smoke test-python ## every test: ctest, ASan+UBSan, valgrind, fuzz smoke, Python

# OpenBLAS on one thread: ctest already runs JOBS programs at once, and OpenBLAS's own
# threads on top of them tripled the wall time of the Campbell tests (29 s against 9 s).
test-unit: build ## ctest on the normal build
	mkdir -p $(BUILD)/test-times
	cd $(BUILD) && OPENBLAS_NUM_THREADS=1 GD_TEST_TIMES=$(CURDIR)/$(BUILD)/test-times \
	    ctest --output-on-failure -j$(JOBS)

# The sanitizer build is clang's, with the libFuzzer targets in it: one more compile of
# the library serves the sanitizer tests and the fuzz smoke run (clang also checks
# float-to-int casts). -O1: with the fuzzer's coverage hooks, -O0 ran the tests 2.2x
# slower (test_monodromy 2.22 s against 0.96 s of CPU).
asan-build: deps ## the AddressSanitizer + UBSan build into $(ASAN_BUILD)
	@CC=clang cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG="-g -O1" \
	    -DGD_SANITIZE=ON -DGD_FUZZ=ON >/dev/null
	@cmake --build $(ASAN_BUILD) -j$(JOBS)

# ctest starts the costliest programs first when it knows their cost: a first sanitizer run
# borrows the normal build's record (the same programs, each slower by a similar factor).
# The sanitizer build runs the test cases that took at most ASAN_MAX_CPU seconds of CPU in
# the normal build (test-unit's record, $(BUILD)/test-times; without it, every case): the
# few costlier ones, solver sweeps and long integrations, run 2-3x slower there and
# repeat code the cheaper cases already run under the sanitizers. ASAN_MAX_CPU=1e9 runs all.
# 0.5 s since 2026-11-26: the clean-clone run had reached 631 s; the 24 cases of 0.5-1 s
# (15 s native) cost about 25 s of its wall time.
ASAN_MAX_CPU ?= 0.5
test-asan: asan-build ## ctest on the sanitizer build
	@mkdir -p $(ASAN_BUILD)/Testing/Temporary; cost=Testing/Temporary/CTestCostData.txt; \
	    [ -f $(ASAN_BUILD)/$$cost ] || [ ! -f $(BUILD)/$$cost ] || cp $(BUILD)/$$cost $(ASAN_BUILD)/$$cost
	@# the structure checks and the install test read the sources and install the same
	@# library: the normal build's run covers them
	cd $(ASAN_BUILD) && OPENBLAS_NUM_THREADS=1 GD_TEST_TIMES_IN=$(CURDIR)/$(BUILD)/test-times \
	    GD_TEST_MAX_CPU=$(ASAN_MAX_CPU) ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	    ctest --output-on-failure -j$(JOBS) -E '^(test_install|structure_.*)$$'

# The test programs, then the CLI itself on the examples and on error paths. The CLI test
# programs (test_cli*) are left out: they run the CLI through /bin/sh, which valgrind does
# not follow, so under valgrind they only re-ran the normal build's CLI tests; the CLI
# runs below are valgrind's cover of the CLI, JOBS at a time (each writes its own folder;
# the study --resume follows the run it resumes).
# Valgrind runs code 20-170x slower than the native build, so it runs the test cases that
# took at most VALGRIND_MAX_CPU seconds of CPU in the normal build (test-unit records each
# case's CPU time in $(BUILD)/test-times; a program without a fresh record is run natively
# once first). The costlier cases, the solver sweeps and long integrations (52 of 426 on
# 2026-11-25, 96 % of the native CPU), run in the normal build (and the sanitizer build
# below 1 s); every program still runs under valgrind. The periodic CLI run leaves out the
# Floquet multipliers (0.42 of its 0.47 s natively, a minute under valgrind): the Mathieu
# run computes them. 0.05 s since 2026-11-26 (was 0.1): the 46 cases of 0.05-0.1 s took
# 3.3 s natively, about two minutes of valgrind CPU, in a clean-clone run that had reached
# 631 s (606 s at 0.07).
VALGRIND_MAX_CPU ?= 0.05
memcheck: build ## the test programs under valgrind
	@set -e; mkdir -p $(BUILD)/test-times; for t in $(BUILD)/test_*; do \
	    [ -f $$t ] && [ -x $$t ] && [ "$$(head -c 4 $$t | tail -c 3)" = ELF ] || continue; \
	    name=$$(basename $$t); \
	    case $$name in test_cli_*|test_cli) continue;; esac; \
	    times=$(BUILD)/test-times/$$name.txt; \
	    [ $$times -nt $$t ] || OPENBLAS_NUM_THREADS=1 GD_TEST_TIMES=$(BUILD)/test-times $$t >/dev/null; \
	    skip=$$(awk -v max=$(VALGRIND_MAX_CPU) '$$2 > max { printf "%s%s", n++ ? "," : "-", $$1 }' $$times); \
	    echo "$$t$${skip:+ $$skip}"; done | \
	GD_VG="$(VALGRIND)" xargs -P $(JOBS) -L 1 sh -fc 'echo "valgrind $$*"; \
	    OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 $$GD_VG "$$@" >/dev/null || \
	    { echo "valgrind failed: $$*" >&2; exit 255; }' sh; \
	out=$$(mktemp -d); \
	printf '%s\n' \
	    "check examples/rig2018.yaml" \
	    "modal examples/rig2018.yaml --speed 3000rpm --json" \
	    "modal examples/chen1998_gear_pair.yaml --out $$out/modal" \
	    "modal examples/chen1998_gear_pair.yaml --set meshes.*.stiffness=5e7 --set meshes.mesh.base_radius=[12mm,54mm]" \
	    "matrices examples/rig2018.yaml --speed 3000rpm --out $$out/m" \
	    "matrices examples/chen1998_gear_pair.yaml --format json --out $$out/j" \
	    "mesh-stiffness examples/helical_pair1.yaml --set meshes.pair1.geometry.helix_angle=15deg" \
	    "mesh-stiffness examples/helical_pair1.yaml --json" \
	    "campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:4 --json" \
	    "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --freq 100:26000:20 --json" \
	    "unbalance examples/chen1998_gear_pair.yaml --speeds 100:6000:8 --json" \
	    "transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet --json" \
	    "transient examples/rig2018.yaml --set shafts.*.elements_per_section=1 --duration 1ms --output-interval 20us --method galpha --reduce 5kHz --quiet" \
	    "transient examples/chen1998_gear_pair.yaml --speed 1500 --duration 20ms --poincare shaft_a --quiet --json" \
	    "transient examples/chen1998_gear_pair.yaml --sweep-speeds 1000:2000:2 --poincare shaft_a --settle 5rev --points 4 --both-directions --quiet --out $$out/sw" \
	    "modal examples/chen1998_gear_pair.yaml --plot $$out/modes.svg" \
	    "report tests/plot/study.yaml --speeds 0:3000rpm:3 --freq-points 20 --out $$out/report.html" \
	    "modal examples/kumar2011_coupled.yaml --directional --group shaft --dofs x,y,rz --json" \
	    "study examples/studies/chen1998_mesh_stiffness.yaml --out $$out/st --shard 1/4 --threads 2" \
	    "periodic tests/plot/mathieu_pair.yaml --speeds 695:705:2 --harmonics 2 --plot $$out/periodic.svg" \
	    "periodic examples/chen1998_gear_pair.yaml --speeds 500:700:2 --harmonics 3 --no-stability --json --out $$out/p" \
	    "modal examples/chen1998_gear_pair.yaml --plot $$out/modes.png" | \
	GD_VG="$(VALGRIND)" GD="$(BUILD)/geardyn" xargs -P $(JOBS) -I{} sh -fc 'echo "valgrind geardyn $$1"; \
	    OPENBLAS_NUM_THREADS=1 $$GD_VG $$GD $$1 >/dev/null || \
	    { echo "valgrind failed: geardyn $$1" >&2; exit 255; }' sh {}; \
	echo "valgrind geardyn study examples/studies/chen1998_mesh_stiffness.yaml --out $$out/st --shard 1/4 --resume"; \
	OPENBLAS_NUM_THREADS=1 $(VALGRIND) $(BUILD)/geardyn study examples/studies/chen1998_mesh_stiffness.yaml --out $$out/st --shard 1/4 --resume >/dev/null; \
	printf '%s\n' \
	    "modal examples/missing.yaml" \
	    "modal examples/rig2018.yaml --speed fast" \
	    "check examples/helical_pair1.yaml" \
	    "check examples/rig2018.yaml --set bearings.*.k=-1" \
	    "check examples/rig2018.yaml --set shafts.nope.name=x" \
	    "matrices examples/rig2018.yaml --out $$out/bad --set disks.0.mass=-1" \
	    "transient examples/chen1998_gear_pair.yaml --sweep-speeds 1000:2000:3 --poincare nope" \
	    "modal examples/chen1998_gear_pair.yaml --plot $$out/modes.bmp" \
	    "modal examples/kumar2011_torsional.yaml --modes 1 --plot $$out/rigid.svg" \
	    "check examples" \
	    "check tests/model_file/hostile/element_length_1e-9.yaml" \
	    "study examples/rig2018.yaml --out $$out/badstudy" \
	    "periodic examples/chen1998_gear_pair.yaml --speeds 1:2:3 --subharmonic 0" | \
	GD_VG="$(VALGRIND)" GD="$(BUILD)/geardyn" xargs -P $(JOBS) -I{} sh -fc \
	    'echo "valgrind geardyn $$1 (must fail with exit 2)"; rc=0; \
	    OPENBLAS_NUM_THREADS=1 $$GD_VG $$GD $$1 >/dev/null 2>&1 || rc=$$?; \
	    [ $$rc -eq 2 ] || { echo "geardyn $$1: exit $$rc, expected 2" >&2; exit 255; }' sh {}; \
	rm -rf $$out; echo "valgrind: all test programs and CLI runs clean"

# libFuzzer (clang): fuzz/fuzz_model.c over the model reader and the system build, and
# fuzz/fuzz_inputs.c over study files, --set paths, gear-pair files and periodic options.
# `make fuzz FUZZ_TARGET=fuzz_inputs FUZZ_SECONDS=600` grows $(FUZZ_BUILD)/corpus-TARGET
# from the seeds; a crash is written to $(FUZZ_BUILD)/crash-* (replay: TARGET FILE).
# `make test` runs FUZZ_RUNS inputs of each from a fixed seed (seconds), writing nothing here,
# with the targets of the sanitizer build; `make fuzz` builds optimised ones in $(FUZZ_BUILD).
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_RUNS    ?= 20000
# fuzz_inputs solves models and periodic branches (about 100 inputs/s): fewer
FUZZ_RUNS_INPUTS ?= 2000
FUZZ_TARGET  ?= fuzz_model
FUZZ_FLAGS_COMMON = -max_len=8192 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1
FUZZ_FLAGS_fuzz_model  = -dict=fuzz/model.dict $(FUZZ_FLAGS_COMMON)
FUZZ_FLAGS_fuzz_inputs = -dict=fuzz/inputs.dict $(FUZZ_FLAGS_COMMON)
FUZZ_SEEDS_fuzz_model  = examples tests/model_file/hostile
FUZZ_SEEDS_fuzz_inputs = fuzz/seeds
FUZZ_ENV      = OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 \
                UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fuzz-build: deps ## the libFuzzer targets (clang)
	@CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGD_FUZZ=ON \
	    -DGD_BUILD_TESTS=OFF -DGD_BUILD_SHARED=OFF >/dev/null
	@cmake --build $(FUZZ_BUILD) -j$(JOBS) --target fuzz_model fuzz_inputs

fuzz: fuzz-build ## run the fuzz targets
	@mkdir -p $(FUZZ_BUILD)/corpus-$(FUZZ_TARGET)
	$(FUZZ_ENV) $(FUZZ_BUILD)/$(FUZZ_TARGET) $(FUZZ_FLAGS_$(FUZZ_TARGET)) -artifact_prefix=$(FUZZ_BUILD)/ \
	    -max_total_time=$(FUZZ_SECONDS) $(FUZZ_BUILD)/corpus-$(FUZZ_TARGET) $(FUZZ_SEEDS_$(FUZZ_TARGET))

fuzz-smoke: asan-build ## a short fuzz run
	@set -e; for t in fuzz_model fuzz_inputs; do \
	    out=$$(mktemp -d); rc=0; \
	    if [ $$t = fuzz_model ]; then flags="$(FUZZ_FLAGS_fuzz_model)"; seeds="$(FUZZ_SEEDS_fuzz_model)"; \
	        runs=$(FUZZ_RUNS); \
	    else flags="$(FUZZ_FLAGS_fuzz_inputs)"; seeds="$(FUZZ_SEEDS_fuzz_inputs)"; \
	        runs=$(FUZZ_RUNS_INPUTS); fi; \
	    $(FUZZ_ENV) $(ASAN_BUILD)/$$t $$flags -artifact_prefix=$$out/ -runs=$$runs -seed=1 \
	        $$out $$seeds 2>$$out.log || rc=$$?; \
	    echo "$$t:"; grep -E "^(stat::number_of_executed_units|INFO: Seed)" $$out.log || true; \
	    [ $$rc -eq 0 ] || cat $$out.log; rm -rf $$out $$out.log; [ $$rc -eq 0 ]; done

bench: build ## the benchmarks (bench/run.sh)
	bash bench/run.sh $(BUILD)

format: ## clang-format every C file
	clang-format -i $$(git ls-files "*.c" "*.h")

clean: ## remove the build folders
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
