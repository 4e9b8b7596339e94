# Thin wrapper over CMake: `make demo` and `make test` on a fresh Debian machine.
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PACKAGES = cmake make gcc g++ pkg-config liblua5.4-dev libglfw3-dev libosmesa6-dev libegl-dev \
           libegl-mesa0 libgl1-mesa-dri libgl1 libglx-mesa0 libtinygltf-dev libpng-dev libjpeg62-turbo-dev libtiff-dev libopenexr-dev libembree-dev xvfb xauth \
           openexr openimageio-tools libxml2-utils ffmpeg

.PHONY: all deps farm-deps build demo test test-farm fuzz matrix install clean

all: build

# Installs the packages named in $(1) that are missing, when run as root;
# otherwise says what to install.
define install_missing
	@missing=$$(for p in $(1); do dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing: $$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null || exit 1; \
	  else \
	    echo "missing packages; run: sudo apt-get install -y $$missing"; exit 1; \
	  fi; \
	fi
endef

deps:
	$(call install_missing,$(PACKAGES))

# The render-farm test's packages (a one-node Slurm cluster).
FARM_PACKAGES = slurm-wlm munge
farm-deps:
	$(call install_missing,$(FARM_PACKAGES))

# The Slurm test alone: a one-node cluster on this machine records an array job.
test-farm: farm-deps build
	@cd $(BUILD) && ctest --output-on-failure -R cli_slurm_test

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out/demo
	$(BUILD)/caustica render scenes/demo.lua -o out/demo/demo.png --timings
	$(BUILD)/caustica record scenes/demo.lua -o out/demo/frames --frames 0:59 --size 256x256
	@echo "demo images: out/demo/demo.png and out/demo/frames/frame_0000.png .. frame_0059.png"

# Installs the binary in $(PREFIX)/bin and its shaders, Lua modules,
# scenes, assets and docs in $(PREFIX)/share (it needs no source tree then).
PREFIX ?= /usr/local
install: build
	@cmake --install $(BUILD) --prefix "$(PREFIX)"
	@echo "installed $(PREFIX)/bin/caustica (data in $(PREFIX)/share/caustica)"

# The technique x case matrix (docs/OPTICS_MATRIX.md), written again from its test.
matrix: build
	@tests/optics_matrix.sh $(BUILD)/caustica

# ctest ends with its timing line; the summary is repeated last so that the
# run's final line says what passed.
test: build
	@cd $(BUILD) && { ctest --output-on-failure -j $(JOBS); echo $$? > ctest.rc; } 2>&1 | tee ctest.log; \
	 grep -E 'tests passed|No tests were found' ctest.log | tail -n 1; exit $$(cat ctest.rc)

# libFuzzer harnesses (tests/fuzz): a clang build with ASan + UBSan, each
# harness run FUZZ_SECONDS on a copy of its seed corpus. A crash (or
# timeout) input is copied into $(FUZZ_KEEP)/crashes_<harness>/: by default
# tests/fuzz, where ctest replays it in every build from then on. CI keeps
# them in the fuzz build instead (.ci/run), so that the tests it runs are the
# ones committed. Skipped, with a message, where clang is missing.
FUZZ_SECONDS ?= 60
FUZZ_BUILD ?= build-fuzz
FUZZ_KEEP ?= tests/fuzz
fuzz: deps
	@if ! command -v clang >/dev/null 2>&1; then echo "make fuzz: skipped (clang is missing: apt-get install clang)"; exit 0; fi; \
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCAUSTICA_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null && \
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_gltf fuzz_script fuzz_png fuzz_jpeg fuzz_exr fuzz_hdr fuzz_pfm fuzz_bench_csv fuzz_reference_part fuzz_test_report >/dev/null || exit 1; \
	status=0; \
	for h in gltf script png jpeg exr hdr pfm bench_csv reference_part test_report; do \
	  rm -rf $(FUZZ_BUILD)/corpus_$$h $(FUZZ_BUILD)/artifacts_$$h; mkdir -p $(FUZZ_BUILD)/corpus_$$h $(FUZZ_BUILD)/artifacts_$$h; \
	  if [ $$h = script ]; then tests/fuzz/script_corpus.sh $(FUZZ_BUILD)/corpus_$$h; \
	  else cp tests/fuzz/corpus_$$h/* $(FUZZ_BUILD)/corpus_$$h/; fi; \
	  echo "fuzz_$$h: $(FUZZ_SECONDS) s"; \
	  ASAN_OPTIONS=detect_leaks=0 CAUSTICA_ROOT=$(CURDIR) $(FUZZ_BUILD)/fuzz_$$h -max_total_time=$(FUZZ_SECONDS) \
	    -max_len=65536 -timeout=60 -rss_limit_mb=3072 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts_$$h/ $(FUZZ_BUILD)/corpus_$$h >$(FUZZ_BUILD)/fuzz_$$h.log 2>&1; \
	  grep -E "^stat::number_of_executed_units|^Done" $(FUZZ_BUILD)/fuzz_$$h.log | sed "s/^/  /"; \
	  for a in $(FUZZ_BUILD)/artifacts_$$h/*; do \
	    [ -e "$$a" ] || continue; status=1; mkdir -p $(FUZZ_KEEP)/crashes_$$h; cp "$$a" $(FUZZ_KEEP)/crashes_$$h/; \
	    echo "  found $$(basename $$a): kept as $(FUZZ_KEEP)/crashes_$$h/$$(basename $$a) (log: $(FUZZ_BUILD)/fuzz_$$h.log)"; \
	    grep -m 8 -E "ERROR: |SUMMARY|/src/" $(FUZZ_BUILD)/fuzz_$$h.log | sed "s/^/    /"; \
	  done; \
	done; \
	[ $$status = 0 ] && echo "fuzz: no crashes"; exit $$status

clean:
	rm -rf $(BUILD) out
