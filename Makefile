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
# benchmarks and second opinions; the extras hold its convex decomposers),
# gnuplot (benchmark plots).
DEB_PACKAGES := build-essential cmake pkg-config clang-format libcgal-dev libgmp-dev libmpfr-dev \
  libboost-dev libassimp-dev libxml2-dev libfcl-dev libccd-dev libbullet-dev libbullet-extras-dev gnuplot-nox

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
	@$(MAKE) --no-print-directory meshes

# Real meshes for the FCL comparison (test_fcl_model, bench_models): bunny00,
# elephant and armadillo from the CGAL sample data (Debian libcgal-demo,
# docs: /work/shared/models/cgal_demo_meshes.md). When the package's
# data.tar.gz is not installed, the .deb is downloaded (not installed: it
# pulls Qt) and only the three OFF files are extracted into $(MESH_DATA),
# the path tests/CMakeLists.txt gives the programs (PROXIMA_MESH_DATA).
# Without network or root the step says so and the mesh tests skip.
MESH_DATA ?= $(CURDIR)/build/meshdata
CGAL_DATA_TGZ ?= /usr/share/doc/libcgal-dev/data.tar.gz
MESH_FILES := data/meshes/bunny00.off data/meshes/elephant.off data/meshes/armadillo.off

.PHONY: meshes
meshes:
	@set -e; dir="$(MESH_DATA)"; have=1; \
	for f in $(MESH_FILES); do [ -s "$$dir/$$(basename $$f)" ] || have=0; done; \
	if [ $$have = 1 ]; then exit 0; fi; \
	mkdir -p "$$dir"; tmp="$$dir/extract"; rm -rf "$$tmp"; mkdir -p "$$tmp"; \
	if [ -s "$(CGAL_DATA_TGZ)" ]; then \
	  tar -xzf "$(CGAL_DATA_TGZ)" -C "$$tmp" $(MESH_FILES); \
	else \
	  echo "meshes: $(CGAL_DATA_TGZ) absent; downloading libcgal-demo (not installing it)"; \
	  deb=""; \
	  if ( cd "$$tmp" && apt-get download -q libcgal-demo ) > "$$tmp/apt.log" 2>&1; then :; \
	  elif [ "$$(id -u)" = 0 ]; then \
	    apt-get update -qq > /dev/null 2>&1 || true; \
	    ( cd "$$tmp" && apt-get download -q libcgal-demo ) > "$$tmp/apt.log" 2>&1 || true; \
	  fi; \
	  deb=$$(ls "$$tmp"/libcgal-demo_*.deb 2>/dev/null | head -n 1); \
	  if [ -z "$$deb" ]; then \
	    echo "meshes: warning: could not download libcgal-demo (see $$tmp/apt.log);" \
	         "the real-mesh tests will skip" >&2; exit 0; \
	  fi; \
	  dpkg-deb --fsys-tarfile "$$deb" | tar -xO ./usr/share/doc/libcgal-dev/data.tar.gz \
	    | tar -xz -C "$$tmp" $(MESH_FILES); \
	fi; \
	for f in $(MESH_FILES); do mv "$$tmp/$$f" "$$dir/"; done; rm -rf "$$tmp"; \
	echo "meshes: $$(cd "$$dir" && ls *.off | tr '\n' ' ')in $$dir"

configure:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPROXIMA_WERROR=ON

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: deps
	$(MAKE) build
	./$(BUILD)/examples/proxima_puma_cell --models models --out $(BUILD) --pieces approximate --exact-every 5
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
PUMA_URDF = $(CURDIR)/models/puma560/nimasarli_puma560_description/urdf/puma560.urdf
test-install: build
	rm -rf $(STAGE) $(CONSUMER)
	cmake --install $(BUILD) --prefix $(STAGE) > /dev/null
	cmake -S tests/consumer -B $(CONSUMER) -DCMAKE_PREFIX_PATH=$(STAGE) > /dev/null
	cmake --build $(CONSUMER) > /dev/null
	$(CONSUMER)/consumer
	$(CONSUMER)/consumer_io $(TEAPOT) $(PUMA_URDF)
	cp tests/consumer/main.c $(CONSUMER)/app.c
	cp tests/consumer/main_io.c $(CONSUMER)/app_io.c
	cd $(CONSUMER) && export PKG_CONFIG_PATH=$(STAGE)/lib/pkgconfig && \
	  cc app.c -o app $$(pkg-config --cflags --libs proxima) && ./app && \
	  cc app_io.c -o app_io $$(pkg-config --cflags --libs proxima-io) && ./app_io $(TEAPOT) $(PUMA_URDF)
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
# CI): writes docs/bench/convex.csv, convex_tables.md, hybrid.csv, hybrid.md,
# models.csv, models.md, scene.csv, scene.md and regenerates the plots.
# `make bench-models` runs only the model benchmark (real meshes against
# FCL's BVHModel<OBBRSS>), `make bench-scene` only the scene benchmark.
bench: deps
	$(MAKE) build
	./$(BUILD)/bench/bench_convex --out docs/bench
	./$(BUILD)/bench/bench_hybrid --out docs/bench
	gnuplot docs/bench/plot_convex.gp
	gnuplot docs/bench/plot_hybrid.gp
	$(MAKE) bench-models-run
	$(MAKE) bench-scene-run

.PHONY: bench-models bench-models-run
bench-models: deps
	$(MAKE) build
	$(MAKE) bench-models-run

bench-models-run:
	./$(BUILD)/bench/bench_models --meshes $(MESH_DATA) --models models --out docs/bench
	gnuplot docs/bench/plot_models.gp

# Issue 11 section 5 (about 10 minutes on the 2-core machine; not part of
# CI, only its smoke ctest is): px_scene against FCL's
# DynamicAABBTreeCollisionManager + fcl::distance and brute force all pairs
# on 100 .. 10,000 moving bodies; writes docs/bench/scene.csv, scene.md and
# scene.png.
.PHONY: bench-scene bench-scene-run
bench-scene: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPROXIMA_WERROR=ON
	cmake --build $(BUILD) -j $(JOBS) --target bench_scene
	$(MAKE) bench-scene-run

bench-scene-run:
	./$(BUILD)/bench/bench_scene --models models --out docs/bench
	gnuplot docs/bench/plot_scene.gp

# Issue 10 section 3 (about 20 minutes on the 2-core machine; not part of
# CI): PX_PIECES_APPROXIMATE against Bullet's ConvexDecomposition and HACD
# and one hull per part; writes docs/bench/decomposition.csv,
# decomposition.md, decomposition_curves.dat and decomposition.png.
.PHONY: bench-decomp bench-decomp-run
bench-decomp: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPROXIMA_WERROR=ON
	cmake --build $(BUILD) -j $(JOBS) --target bench_decomp
	$(MAKE) bench-decomp-run

bench-decomp-run:
	./$(BUILD)/bench/bench_decomp --meshes $(MESH_DATA) --models models --out docs/bench
	gnuplot docs/bench/plot_decomposition.gp

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
