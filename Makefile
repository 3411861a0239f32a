# The two commands of the README. Each installs what it needs on a fresh
# Debian 12 machine (as root), configures CMake and builds.
#   make demo   runs the library's main job on the models it ships
#   make test   builds and runs the whole test suite, then again under ASan+UBSan
# Only these two and `make deps` install packages; `make build` never does.
SHELL := /bin/bash
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD ?= build
BUILD_ASAN ?= build-asan
ABS_BUILD = $(abspath $(BUILD))

# Debian packages the build needs: compiler and CMake, CGAL (hulls, exact
# ground truth), GMP/MPFR, Assimp (files), FCL/libccd/Bullet (peers in
# benchmarks and second opinions), gnuplot (benchmark plots).
DEB_PACKAGES := build-essential cmake pkg-config clang-format libcgal-dev libgmp-dev libmpfr-dev \
  libboost-dev libassimp-dev libfcl-dev libccd-dev libbullet-dev gnuplot-nox

.PHONY: all deps configure build demo test test-release test-asan test-install test-embed format format-check bench clean

all: build

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  if [ "$$(id -u)" != 0 ]; then echo "error: missing packages and not root; install:$$missing" >&2; exit 1; fi; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  apt-get update -qq && apt-get install -y -qq --no-install-recommends $$missing; \
	fi

configure:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPROXIMA_WERROR=ON

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: deps
	$(MAKE) build
	./$(BUILD)/examples/proxima_demo --models models
	./$(BUILD)/examples/proxima_model_demo --models models

test-release: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-asan:
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPROXIMA_SANITIZE=ON -DPROXIMA_WERROR=ON \
	  -DPROXIMA_BUILD_BENCH=OFF
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS)

# Install into a scratch prefix, then build outside projects against it:
# with find_package(proxima) (core and io), and with exactly the link lines
# of the README (pkg-config proxima, pkg-config proxima-io).
STAGE = $(ABS_BUILD)/stage
CONSUMER = $(ABS_BUILD)/consumer
TEAPOT = $(CURDIR)/models/teapot/trimesh_mit/teapot.stl
test-install: build
	rm -rf $(STAGE) $(CONSUMER)
	cmake --install $(BUILD) --prefix $(STAGE) > /dev/null
	cmake -S tests/consumer -B $(CONSUMER) -DCMAKE_PREFIX_PATH=$(STAGE) > /dev/null
	cmake --build $(CONSUMER) > /dev/null
	$(CONSUMER)/consumer
	$(CONSUMER)/consumer_io $(TEAPOT)
	cp tests/consumer/main.c $(CONSUMER)/app.c
	cp tests/consumer/main_io.c $(CONSUMER)/app_io.c
	cd $(CONSUMER) && export PKG_CONFIG_PATH=$(STAGE)/lib/pkgconfig && \
	  cc app.c -o app $$(pkg-config --cflags --libs proxima) && ./app && \
	  cc app_io.c -o app_io $$(pkg-config --cflags --libs proxima-io) && ./app_io $(TEAPOT)
	@echo "test-install: find_package and the README's pkg-config lines build and run"

# A parent project that embeds proxima with add_subdirectory: it builds, and
# none of proxima's settings leak into the parent (tests/parent).
test-embed:
	rm -rf $(ABS_BUILD)/parent
	cmake -S tests/parent -B $(ABS_BUILD)/parent -DPROXIMA_SOURCE=$(CURDIR) > /dev/null
	cmake --build $(ABS_BUILD)/parent -j $(JOBS) --target parent_app > /dev/null
	$(ABS_BUILD)/parent/parent_app
	@echo "test-embed: proxima builds inside a parent project and leaves its settings alone"

format-check:
	@files=$$(git ls-files '*.c' '*.h' '*.cpp' 2>/dev/null); \
	if [ -n "$$files" ]; then clang-format --dry-run --Werror $$files; fi

format:
	clang-format -i $$(git ls-files '*.c' '*.h' '*.cpp')

test: deps
	$(MAKE) format-check test-release test-install test-embed test-asan
	@echo "make test: all suites passed (release, install, ASan+UBSan)"

# The full benchmark (about 40 minutes on the 2-core machine; not part of
# CI): writes docs/bench/convex.csv, convex_tables.md, hybrid.csv, hybrid.md
# and regenerates the plots.
bench: build
	./$(BUILD)/bench/bench_convex --out docs/bench
	./$(BUILD)/bench/bench_hybrid --out docs/bench
	gnuplot docs/bench/plot_convex.gp
	gnuplot docs/bench/plot_hybrid.gp

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
