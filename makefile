# petsc-vshmm: convenience targets around CMake (GNU make).
#   make demo        install missing Debian packages, build, run examples/ode/demo.sh
#   make check       install missing Debian packages, build, run all tests (ctest)
#   make build       configure and build in $(BUILD_DIR)
#   make install PREFIX=/some/prefix
#   make figures     build, then regenerate docs/figures/*.png, *.svg (gnuplot; a few minutes)
#   make bench       install the benchmark's packages too (SUNDIALS, python3), build, run the full
#                    work-precision benchmark (bench/run_bench.py; about half an hour) and regenerate
#                    the tables and figures of docs/performance.md
#   make bench-quick the same with a reduced sweep of every problem and method (a few minutes),
#                    into $(BUILD_DIR)/bench-quick/ only (docs untouched)
#   make mutants     mutation check of the tests (tools/mutants.sh, tools/mutants.txt; long:
#                    one rebuild and test run per mutant, in a copy of the tree under /tmp)
#   make check-nofftw  build and test as if FFTW were absent (-DVSHMM_WITH_FFTW=OFF: the time
#                    stepper without the spectral component) in $(BUILD_DIR)-nofftw
#   make format-check  list the C/C++ files that clang-format (.clang-format at the root) would
#                    change, and fail if there are any (part of make check)
#   make clean       remove $(BUILD_DIR)
# Variables: BUILD_DIR (build), BUILD_TYPE (Release), JOBS (2), PREFIX (/usr/local),
#            CMAKE_FLAGS (extra configure options), CTEST_FLAGS (extra ctest options).

BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
PREFIX ?= /usr/local
CMAKE_FLAGS ?=
CTEST_FLAGS ?=

DEB_PACKAGES := petsc-dev libfftw3-dev libgtest-dev cmake pkg-config make g++ \
                libpetsc3.18-dev-examples gnuplot-nox valgrind clang-format
# only for make bench, bench-quick: SUNDIALS for the peer integrators (optional: without it the
# benchmark skips CVODE and ARKODE), Python 3 for the driver script
BENCH_PACKAGES := libsundials-dev python3

.PHONY: all deps configure build check check-nofftw format-check demo figures install clean mutants bench bench-quick bench-build
.NOTPARALLEL:
MAKEFLAGS += --no-print-directory

all: build

# Debian packages: installed with apt-get when missing and running as root; otherwise listed.
deps:
	@if ! command -v dpkg-query >/dev/null 2>&1; then \
	  echo "make deps: no dpkg-query (not Debian?); need: $(DEB_PACKAGES)"; exit 0; \
	fi; \
	missing=; \
	for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	if [ "$$(id -u)" = 0 ]; then \
	  echo "Installing:$$missing"; \
	  apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $$missing; \
	else \
	  echo "make deps: missing Debian packages:$$missing"; \
	  echo "  install them with: sudo apt-get install --no-install-recommends$$missing"; \
	fi

$(BUILD_DIR)/CMakeCache.txt:
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS)

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS)

build: deps $(BUILD_DIR)/CMakeCache.txt
	cmake --build $(BUILD_DIR) -j $(JOBS)

check: build format-check
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS) $(CTEST_FLAGS)

check-nofftw: deps
	cmake -S . -B $(BUILD_DIR)-nofftw -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DVSHMM_WITH_FFTW=OFF $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR)-nofftw -j $(JOBS)
	ctest --test-dir $(BUILD_DIR)-nofftw --output-on-failure -j $(JOBS) $(CTEST_FLAGS)

CLANG_FORMAT ?= clang-format
format-check:
	@command -v $(CLANG_FORMAT) >/dev/null 2>&1 || { echo "make format-check: $(CLANG_FORMAT) not found (Debian: clang-format)"; exit 1; }
	@bad=; for f in $$(git ls-files '*.c' '*.h' '*.cpp' '*.hpp'); do \
	  $(CLANG_FORMAT) --dry-run -Werror "$$f" >/dev/null 2>&1 || bad="$$bad $$f"; \
	done; \
	if [ -n "$$bad" ]; then echo "not formatted as .clang-format says (run $(CLANG_FORMAT) -i on them):"; \
	  for f in $$bad; do echo "  $$f"; done; exit 1; fi; echo "format-check: all C/C++ sources formatted"

demo: build
	sh examples/ode/demo.sh $(BUILD_DIR)

figures: build
	sh docs/figures/make_figures.sh $(BUILD_DIR)
	sh docs/figures/spectral_figures.sh $(BUILD_DIR)

# The benchmark: its packages, a fresh configure (so that a SUNDIALS installed just now is found),
# the build, then the driver script.
bench-build:
	@$(MAKE) deps DEB_PACKAGES="$(DEB_PACKAGES) $(BENCH_PACKAGES)"
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS)
	cmake --build $(BUILD_DIR) -j $(JOBS)

bench: bench-build
	python3 bench/run_bench.py --build $(BUILD_DIR) --docs

bench-quick: bench-build
	python3 bench/run_bench.py --build $(BUILD_DIR) --quick

mutants: deps
	JOBS=$(JOBS) sh tools/mutants.sh

install: build
	cmake --install $(BUILD_DIR) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR)-nofftw
