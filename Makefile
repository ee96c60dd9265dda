# The whole set-up on a fresh Debian bookworm machine:
#   make run    installs what is missing, builds (Release), runs the fleet demo
#   make test   the same set-up, then the whole test suite
# Everything else is plain CMake in $(BUILD_DIR).

BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
# CI turns warnings into errors.
WERROR := $(if $(CI),ON,OFF)

.PHONY: all deps configure build run test bench clean format

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFLEETMAP_WERROR=$(WERROR)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	bash scripts/run-demo.sh $(BUILD_DIR)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD_DIR)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i
