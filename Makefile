# Quick start: `make demo` (the virtual rig end to end) and `make check` (every test).
# Each target installs what it needs (scripts/setup) and builds what is out of date.
.PHONY: demo check setup build firmware asan test test-asan clean

BUILD := build
CTEST_JOBS ?= $(shell nproc)

setup:
	@scripts/setup

$(BUILD)/default/build.ninja: | setup
	@cmake --preset default >/dev/null

$(BUILD)/firmware/build.ninja: | setup
	@cmake --preset firmware >/dev/null

$(BUILD)/asan/build.ninja: | setup
	@cmake --preset asan >/dev/null

build: setup $(BUILD)/default/build.ninja
	@cmake --build --preset default

firmware: setup $(BUILD)/firmware/build.ninja
	@cmake --build --preset firmware

asan: setup $(BUILD)/asan/build.ninja
	@cmake --build --preset asan

test: build firmware
	@ctest --preset default -j $(CTEST_JOBS)

test-asan: asan
	@ctest --preset asan -j $(CTEST_JOBS)

check: test test-asan

# The demo builds only the program it runs, tetrapulse-vision (`tetrapulse demo` is
# that program's), in the same build folder: not the board commands, tests and
# benchmarks, which `make build` and `make check` build.
demo: setup $(BUILD)/default/build.ninja
	@cmake --build --preset default --target tetrapulse-vision
	@scripts/demo $(BUILD)/default

clean:
	rm -rf $(BUILD)
