# Thin wrapper over CMake. `make demo` and `make test` install what is missing first.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX     ?= /usr/local
VALGRIND    = valgrind --quiet --error-exitcode=1 --leak-check=full \
              --errors-for-leak-kinds=definite,indirect --show-possibly-lost=no \
              --trace-children=yes \
              --trace-children-skip='/bin/*,/usr/bin/*'

.PHONY: all deps build install demo test test-unit test-asan memcheck bench format clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

# The libraries, the CLI, the headers, geardyn.pc and the CMake package under PREFIX.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

demo: build
	./$(BUILD)/geardyn check examples/rig2018.yaml
	@echo
	./$(BUILD)/geardyn modal examples/rig2018.yaml --speed 3000rpm --modes 12

# Every test: the normal build, then AddressSanitizer + UndefinedBehaviorSanitizer,
# then valgrind on the normal build.
test: test-unit test-asan memcheck

test-unit: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

test-asan: deps
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DGD_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN_BUILD) -j$(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j$(JOBS)

# The test programs, then the CLI itself on the examples and on error paths (the CLI
# tests run it through /bin/sh, which valgrind does not follow).
# The two Campbell sweeps over many speeds take minutes under valgrind; they run in the
# normal and sanitizer builds.
VALGRIND_SKIP_test_campbell = -threads_and_methods_agree,critical_speeds
VALGRIND_SKIP_test_periodic = -backlash_against_transient,sfd_pair_against_transient,backlash_folds_traced_through_unstable_branch,chen_sfd_neimark_sacker_matches_transient
memcheck: build
	@set -e; for t in $(BUILD)/test_*; do \
	    [ -f $$t ] && [ -x $$t ] && [ "$$(head -c 4 $$t | tail -c 3)" = ELF ] || continue; \
	    name=$$(basename $$t); skip=""; \
	    [ "$$name" = test_campbell ] && skip="$(VALGRIND_SKIP_test_campbell)"; \
	    [ "$$name" = test_periodic ] && skip="$(VALGRIND_SKIP_test_periodic)"; \
	    echo "valgrind $$t $$skip"; OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=2 $(VALGRIND) $$t $$skip >/dev/null; done; \
	out=$$(mktemp -d); \
	for args in "check examples/rig2018.yaml" "modal examples/rig2018.yaml --speed 3000rpm --json" \
	            "modal examples/chen1998_gear_pair.yaml --out $$out" \
	            "modal examples/chen1998_gear_pair.yaml --set meshes.*.stiffness=5e7 --set meshes.mesh.base_radius=[12mm,54mm]" \
	            "matrices examples/rig2018.yaml --speed 3000rpm --out $$out/m" \
	            "matrices examples/chen1998_gear_pair.yaml --format json --out $$out/j" \
	            "mesh-stiffness examples/helical_pair1.yaml --set meshes.pair1.geometry.helix_angle=15deg" \
	            "mesh-stiffness examples/helical_pair1.yaml --json" \
	            "campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:4 --json" \
	            "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --freq 100:26000:20 --json" \
	            "unbalance examples/chen1998_gear_pair.yaml --speeds 100:6000:8 --json" \
	            "transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet --json" \
	            "transient examples/chen1998_gear_pair.yaml --speed 1500 --duration 20ms --poincare shaft_a --quiet --json" \
	            "transient examples/chen1998_gear_pair.yaml --sweep-speeds 1000:2000:2 --poincare shaft_a --settle 5rev --points 4 --both-directions --quiet --out $$out/sw" \
	            "periodic examples/chen1998_gear_pair.yaml --speeds 500:700:2 --harmonics 3 --json --out $$out/p"; do \
	    echo "valgrind geardyn $$args"; OPENBLAS_NUM_THREADS=1 $(VALGRIND) $(BUILD)/geardyn $$args >/dev/null; done; \
	for args in "modal examples/missing.yaml" "modal examples/rig2018.yaml --speed fast" \
	            "check examples/helical_pair1.yaml" \
	            "check examples/rig2018.yaml --set bearings.*.k=-1" \
	            "check examples/rig2018.yaml --set shafts.nope.name=x" \
	            "matrices examples/rig2018.yaml --out $$out/bad --set disks.0.mass=-1" \
	            "transient examples/chen1998_gear_pair.yaml --sweep-speeds 1000:2000:3 --poincare nope" \
	            "periodic examples/chen1998_gear_pair.yaml --speeds 1:2:3 --subharmonic 0"; do \
	    echo "valgrind geardyn $$args (must fail with exit 2)"; \
	    rc=0; OPENBLAS_NUM_THREADS=1 $(VALGRIND) $(BUILD)/geardyn $$args >/dev/null 2>&1 || rc=$$?; \
	    [ $$rc -eq 2 ] || { echo "exit $$rc, expected 2"; exit 1; }; done; \
	rm -rf $$out; echo "valgrind: all test programs and CLI runs clean"

bench: build
	bash bench/run.sh $(BUILD)

format:
	clang-format -i $$(git ls-files "*.c" "*.h")

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
