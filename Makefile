# aniso: the two commands of the README, and a few helpers.
#
#   make demo        install missing Debian packages, build, run the default demo campaign
#   make test        install missing Debian packages, build, run every test but the long ones, check formatting
#   make campaign CONFIG=workflows/configs/paper-spheres.toml OUT=runs/paper-spheres
#                    any campaign (paths from this folder), resumed where it stopped
#   make paper       the paper's study: four shapes at paper size, every stage, the paper's figures and a
#                    generated comparison (runs/paper; REALISATIONS=N seeds per shape; hours: see README)
#   make paper-status  where each run of `make paper` stands (files written per kind of step)
#   make paper-export-partial  what a running `make paper` has finished, into docs/paper-size/in-progress
#   make test-long   the long tests only (label `long`)
#   make format      rewrite all C++ sources with clang-format
#   make clean       remove the build folder
#
# The build lives in build/ and is incremental: configuring again is cheap and
# never deletes anything. Other CMake options: make test CMAKE_ARGS=-DANISO_NATIVE=ON

BUILD      := build
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=
# ctest runs this many tests at once; MPI tests ask for their rank count on top.
TEST_JOBS  ?= 2

# Open MPI refuses to run as root unless told it may (containers, CI machines).
MPI_ENV := OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

.PHONY: all demo campaign paper paper-status paper-export paper-export-partial test test-long format clean deps-test deps-demo configure build build-stages

all: build

deps-test:
	bash scripts/install-deps.sh test

deps-demo:
	bash scripts/install-deps.sh demo

configure:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DANISO_WERROR=ON $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j$(JOBS)

# The five programs a campaign runs, without the tests: what the demo and a campaign need.
STAGE_PROGRAMS := aniso-dem aniso-fabric aniso-probe aniso-voxel aniso-lbm
build-stages: configure
	cmake --build $(BUILD) -j$(JOBS) --target $(STAGE_PROGRAMS)

demo: deps-demo
	$(MAKE) build-stages
	$(MPI_ENV) $(MAKE) -C workflows demo BIN=$(abspath $(BUILD))

# Paths are taken from this folder (workflows/Makefile resolves its own from workflows/).
CONFIG ?= workflows/configs/demo.toml
OUT    ?= runs/campaign
campaign: deps-demo
	$(MAKE) build-stages
	$(MPI_ENV) $(MAKE) -C workflows campaign CONFIG=$(abspath $(CONFIG)) OUT=$(abspath $(OUT)) BIN=$(abspath $(BUILD))

# The paper's whole study as one campaign (workflows/paper.mk); resumes where it stopped.
PAPER_OUT ?= runs/paper
paper: deps-demo
	$(MAKE) build-stages
	$(MPI_ENV) $(MAKE) -C workflows paper BIN=$(abspath $(BUILD)) PAPER_OUT=$(abspath $(PAPER_OUT))

# What a study still running has finished so far (its runs' small results, of the checkpoints done).
PAPER_PARTIAL ?= docs/paper-size/in-progress
paper-export-partial:
	$(MAKE) -C workflows paper-export-partial BIN=$(abspath $(BUILD)) PAPER_OUT=$(abspath $(PAPER_OUT)) \
	  PAPER_EXPORT=$(abspath $(PAPER_PARTIAL))

# Where each run of the study stands (files written per kind of step).
paper-status:
	$(MPI_ENV) $(MAKE) -s -C workflows paper-status BIN=$(abspath $(BUILD)) PAPER_OUT=$(abspath $(PAPER_OUT))

# Its small results into docs/paper-size (per shape) once it has finished (workflows/paper_export.py).
paper-export:
	$(MAKE) -C workflows paper-export BIN=$(abspath $(BUILD)) PAPER_OUT=$(abspath $(PAPER_OUT)) \
	  PAPER_EXPORT=$(abspath docs/paper-size)

test: deps-test
	$(MAKE) build
	cd $(BUILD) && $(MPI_ENV) ctest --output-on-failure -j$(TEST_JOBS) -LE '^long$$'
	cmake --build $(BUILD) --target format-check

test-long: deps-test
	$(MAKE) build
	cd $(BUILD) && $(MPI_ENV) ctest --output-on-failure -L '^long$$'

format: deps-test
	$(MAKE) configure
	cmake --build $(BUILD) --target format

clean:
	rm -rf $(BUILD)
