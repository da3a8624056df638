# BioVision workspace entry points. Every target installs what is missing and builds first.
# Debian's ROS 1 needs the system interpreter: a pyenv python3 first on PATH breaks catkin's CMake.
SHELL := /bin/bash
export PATH := /usr/bin:/bin:$(PATH)
JOBS ?= 2
BUILD_TYPE ?= Release
CATKIN_ARGS := -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON
OUT ?= out

.PHONY: all setup build demo test bench lint clean

all: build

setup:
	@bash scripts/setup.sh

# devel/lib/python3/dist-packages must exist before CMake's first configure: catkin bakes PYTHONPATH into
# build/catkin_generated/setup_cached.sh (used by `make run_tests`) only for directories that exist then,
# so on a fresh clone Python nodes could not import the generated biovision_msgs in rostests.
build: setup
	@mkdir -p devel/lib/python3/dist-packages
	@catkin_make -j$(JOBS) $(CATKIN_ARGS) all tests 2>&1 | grep -vE "^make\[|Built target|^-- " ; test $${PIPESTATUS[0]} -eq 0

demo: build
	@bash scripts/demo.sh $(OUT)/demo

test: build
	@CATKIN_ARGS="$(CATKIN_ARGS)" JOBS=$(JOBS) bash scripts/run_tests.sh

bench: build
	@bash scripts/bench.sh

# catkin_lint and clang-format on a fresh clone of HEAD, ROS-free core libraries in devel/ (scripts/lint.sh).
lint: build
	@bash scripts/lint.sh

clean:
	rm -rf build devel install $(OUT)
