# constrict — the two commands of the README:
#   make demo   install missing Debian packages, build (Release), reconstruct the bundled examples into out/
#   make test   build and run every test through ctest
#   make install  library, headers, CLI and the Python package ($(PREFIX)/lib/python3/dist-packages/constrict)
#   make bench  build Release with the benchmarks, then the whole-process table against CGAL's
#               Delaunay (bench/whole_process.sh -> $(OUT)/bench/table.md; several minutes)
# Variables: BUILD (build dir), JOBS, CMAKE_ARGS (extra cmake flags, e.g. -DCONSTRICT_WERROR=ON), PREFIX,
#   ROUNDS (bench rounds, default 3).

BUILD      ?= build
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=
OUT        ?= out
LAUNCHER   := $(shell command -v ccache >/dev/null 2>&1 && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CLI        := $(BUILD)/cli/constrict

.PHONY: all deps configure build demo test bench install clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(LAUNCHER) $(CMAKE_ARGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@scripts/demo.sh $(CLI) $(OUT)

bench: deps
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DCONSTRICT_BUILD_BENCH=ON -DCONSTRICT_BUILD_TESTS=OFF $(LAUNCHER) $(CMAKE_ARGS)
	cmake --build $(BUILD)-bench -j $(JOBS)
	bench/whole_process.sh $(BUILD)-bench $(OUT)/bench $(or $(ROUNDS),3)
	@echo "micro-benchmarks: $(BUILD)-bench/bench/constrict_bench (see docs/benchmarks.md)"

install: build
	cmake --install $(BUILD) --prefix $(or $(PREFIX),install)

clean:
	rm -rf $(BUILD) $(BUILD)-bench $(OUT)
