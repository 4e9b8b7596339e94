# Thin wrapper over CMake: `make demo` and `make test` on a fresh Debian machine.
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PACKAGES = cmake make gcc g++ pkg-config liblua5.4-dev libglfw3-dev libosmesa6-dev libegl-dev \
           libegl-mesa0 libgl1-mesa-dri libgl1 libglx-mesa0 libtinygltf-dev libpng-dev libembree-dev xvfb xauth

.PHONY: all deps build demo test clean

all: build

# Installs what is missing when run as root; otherwise says what to install.
deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing: $$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null || exit 1; \
	  else \
	    echo "missing packages; run: sudo apt-get install -y $$missing"; exit 1; \
	  fi; \
	fi

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out/demo
	$(BUILD)/caustica render scenes/demo.lua -o out/demo/demo.png --timings
	$(BUILD)/caustica record scenes/demo.lua -o out/demo/frames --frames 0:59 --size 256x256
	@echo "demo images: out/demo/demo.png and out/demo/frames/frame_0000.png .. frame_0059.png"

# ctest ends with its timing line; the summary is repeated last so that the
# run's final line says what passed.
test: build
	@cd $(BUILD) && { ctest --output-on-failure -j $(JOBS); echo $$? > ctest.rc; } 2>&1 | tee ctest.log; \
	 grep -E 'tests passed|No tests were found' ctest.log | tail -n 1; exit $$(cat ctest.rc)

clean:
	rm -rf $(BUILD) out
