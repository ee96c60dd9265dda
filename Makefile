# The whole set-up on a fresh Debian bookworm machine:
#   make run    installs what is missing, builds (Release), runs the simulated-fleet demo
#   make test   the same set-up, then the whole test suite
#   make fuzz   every fuzz target for FUZZ_SECONDS each (clang, libFuzzer; in $(FUZZ_DIR))
# Everything else is plain CMake in $(BUILD_DIR).

BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
# CI turns warnings into errors.
WERROR := $(if $(CI),ON,OFF)

.PHONY: all deps configure build run view-demo demo-maps test fuzz-build fuzz clean format format-check

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFLEETMAP_WERROR=$(WERROR)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# 4 simulated robots explore a 40 m office; a server fuses their tiles; all over DDS on loopback.
# Then the same run with whole grids on the wire, for comparison. About 100 s. Watch it live at
# the URL it prints (http://127.0.0.1:$(VIEW_PORT)/, the web view).
VIEW_PORT ?= 8080
run: build
	$(BUILD_DIR)/cli/fleetmap sim --robots 4 --terrain office --size 40 --duration 40 --out out/demo \
	  --view $(VIEW_PORT) --params docs/config/fleet_params.yaml

# A long run to watch in the browser: 6 robots map a 60 m office for 10 minutes.
view-demo: build
	$(BUILD_DIR)/cli/fleetmap sim --robots 6 --terrain office --size 60 --duration 600 \
	  --no-compare --out out/view-demo --view $(VIEW_PORT)

# The slice on real SLAM maps: a server, two agents, one killed, one leaving (about 15 s).
demo-maps: build
	bash scripts/run-demo.sh $(BUILD_DIR)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The fuzz targets of fuzz/ (docs/testing.md, "Fuzzing"): a clang build of their own with ASan and
# UBSan, then each target for FUZZ_SECONDS (one job each), one line per target; fails on a crash and
# keeps the input in $(FUZZ_DIR)/fuzz/crashes/<target>/.
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 600
fuzz-build: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_COMPILER=clang++ -DFLEETMAP_FUZZ=ON
	cmake --build $(FUZZ_DIR) -j $(JOBS)

fuzz: fuzz-build
	bash scripts/run-fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD_DIR)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

# Fails, naming the files and lines, where the tree has drifted from .clang-format (CI runs it).
format-check: deps
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror
