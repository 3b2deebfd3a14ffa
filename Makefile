# Quick start: `make demo` (the virtual rig end to end) and `make check` (every test).
# Each target installs what it needs (scripts/setup) and builds what is out of date.
.PHONY: demo check setup configure-all configure-check build build-check firmware asan test test-check test-asan clean

BUILD := build
CTEST_JOBS ?= $(shell nproc)
# The default preset's tests spend much of their time waiting on VM guests and on rig
# time: one job more than there are cores keeps the cores busy (on 2 cores its 75 tests
# took 242 s with 2 jobs, 170 s with 3 and 186 s with 4).
CTEST_JOBS_DEFAULT ?= $(shell echo $$(( $$(nproc) + 1 )))

setup:
	@scripts/setup

# make build (and check) configures with tests and benchmarks, also in a folder the demo
# configured without them. make check leaves the parts' own tests (label unit, and the
# parts' reliability tests) to the asan build, which builds and runs every one of them
# under the sanitizers; compiling them a second time with gcc was a third of CI.
$(BUILD)/default/build.ninja: | setup
	@cmake --preset default >/dev/null
define configure_default
	@grep -q '^TETRAPULSE_TESTS:BOOL=ON' $(BUILD)/default/CMakeCache.txt && \
	  grep -q '^TETRAPULSE_BENCH:BOOL=ON' $(BUILD)/default/CMakeCache.txt && \
	  grep -q '^TETRAPULSE_PART_TESTS:BOOL=$(1)' $(BUILD)/default/CMakeCache.txt || \
	  cmake --preset default -DTETRAPULSE_TESTS=ON -DTETRAPULSE_BENCH=ON -DTETRAPULSE_PART_TESTS=$(1) >/dev/null
endef
configure-all: $(BUILD)/default/build.ninja
	$(call configure_default,ON)
configure-check: $(BUILD)/default/build.ninja
	$(call configure_default,OFF)

$(BUILD)/firmware/build.ninja: | setup
	@cmake --preset firmware >/dev/null

$(BUILD)/asan/build.ninja: | setup
	@cmake --preset asan >/dev/null

build: setup configure-all
	@cmake --build --preset default

build-check: setup configure-check
	@cmake --build --preset default

firmware: setup $(BUILD)/firmware/build.ninja
	@cmake --build --preset firmware

asan: setup $(BUILD)/asan/build.ninja
	@cmake --build --preset asan

test: build firmware
	@ctest --preset default -j $(CTEST_JOBS_DEFAULT)

test-check: build-check firmware
	@ctest --preset default -j $(CTEST_JOBS_DEFAULT)

test-asan: asan
	@ctest --preset asan -j $(CTEST_JOBS)

# Every test once: the parts' own under the sanitizers (asan), the rest in the default build.
check: test-check test-asan

# The demo installs only the packages it needs (scripts/setup demo) and builds only the
# program it runs, tetrapulse-vision (`tetrapulse demo` is that program's), in the same
# build folder: a folder it configures itself has no tests and benchmarks, which
# `make build` and `make check` add.
demo:
	@scripts/setup demo
	@[ -f $(BUILD)/default/build.ninja ] || \
	  cmake --preset default -DTETRAPULSE_TESTS=OFF -DTETRAPULSE_BENCH=OFF >/dev/null
	@cmake --build --preset default --target tetrapulse-vision
	@scripts/demo $(BUILD)/default

clean:
	rm -rf $(BUILD)
