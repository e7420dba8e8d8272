# Thin wrapper over CMake. `make demo` and `make test` install what is missing first.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
VALGRIND    = valgrind --quiet --error-exitcode=1 --leak-check=full \
              --errors-for-leak-kinds=definite,indirect --trace-children=yes \
              --trace-children-skip='/bin/*,/usr/bin/*'

.PHONY: all deps build demo test test-unit test-asan memcheck bench format clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

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

memcheck: build
	@set -e; for t in $(BUILD)/test_*; do \
	    echo "valgrind $$t"; OPENBLAS_NUM_THREADS=1 $(VALGRIND) $$t >/dev/null; done; \
	echo "valgrind: all test programs clean"

bench: build
	bash bench/run.sh $(BUILD)

format:
	clang-format -i include/geardyn/*.h src/*.c src/*.h src/*/*.c src/*/*.h cli/*.c cli/*.h tests/*.c tests/*.h

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
