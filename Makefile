# fresnel: top-level driver. `make demo` and `make test` work on a fresh Debian 12 machine.
JOBS        ?= $(shell nproc)
BUILD       ?= build
ASAN_BUILD  ?= build-asan
BUILD_TYPE  ?= Release
FUZZ_SECONDS ?= 60
# ON: compiler warnings are errors (CI: `make test FRESNEL_WERROR=ON`); the gcc builds only, not `make fuzz`.
FRESNEL_WERROR ?= OFF
CMAKE_GEN   := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

WEB_BUILD   ?= build-web

.PHONY: all deps configure build demo test test-fast asan fuzz bench fidelity-report peer-report clean web web-deps web-bench python

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFRESNEL_WERROR=$(FRESNEL_WERROR)

# An existing build folder is reconfigured when FRESNEL_WERROR differs from its cache.
configure: $(BUILD)/CMakeCache.txt
	@grep -qx 'FRESNEL_WERROR:BOOL=$(FRESNEL_WERROR)' $(BUILD)/CMakeCache.txt || cmake -S . -B $(BUILD) -DFRESNEL_WERROR=$(FRESNEL_WERROR)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The Python module alone, into $(BUILD)/python (docs/python.md):
#   PYTHONPATH=$(BUILD)/python python3 -c 'import fresnel'
python: deps configure
	cmake --build $(BUILD) -j $(JOBS) --target fresnel_python

demo: deps
	@$(MAKE) --no-print-directory build
	$(BUILD)/bin/fresnel render -o demo.png --size 1024x768
	@echo "wrote demo.png"

# Every test: unit, GPU (llvmpipe), image and corpus tests in the release build, the web page
# (make web, then web_page_test in headless Chromium: ~1 min to build, ~1 min to test),
# then the loader tests and the corpus again under AddressSanitizer + UBSan.
test: deps
	@$(MAKE) --no-print-directory build
	@$(MAKE) --no-print-directory web
	@scripts/install-test-tools.sh $(BUILD)/node-tools
	@# Configure again: node and the tools installed since the first configure register their tests.
	@cmake $(BUILD) > /dev/null
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	@$(MAKE) --no-print-directory asan

test-fast: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/CMakeCache.txt:
	cmake -S . -B $(ASAN_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFRESNEL_SANITIZE=ON -DFRESNEL_BENCH=OFF -DFRESNEL_VIEWER=OFF \
	  -DFRESNEL_WERROR=$(FRESNEL_WERROR)

# Only what the sanitizer tests need: the loaders' unit tests, the CLI (corpus and hostile-input
# tests) and the fuzz-regression replayers; no viewer, and -O1 -g1 (CMakeLists.txt) to keep CI short.
ASAN_TARGETS := core_test scene_test viewer_test obj_loader_test gltf_compressed_test mesh_ops_test scene_file_test fresnel \
                replay_gltf replay_obj replay_image replay_hdr replay_exr replay_scene_file replay_meshopt \
                replay_draco replay_webp replay_ktx2 replay_zstd ktx2_test basisu_modes_test zstd_decoder_test
asan: $(ASAN_BUILD)/CMakeCache.txt
	@grep -qx 'FRESNEL_WERROR:BOOL=$(FRESNEL_WERROR)' $(ASAN_BUILD)/CMakeCache.txt || cmake -S . -B $(ASAN_BUILD) -DFRESNEL_WERROR=$(FRESNEL_WERROR)
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(ASAN_TARGETS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS) -L sanitize

fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B build-fuzz $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFRESNEL_FUZZ=ON -DFRESNEL_BENCH=OFF
	cmake --build build-fuzz -j $(JOBS)
	scripts/run-fuzzers.sh build-fuzz $(FUZZ_SECONDS)

bench: build
	@scripts/setup-khronos-ref.sh $(BUILD)/khronos-ref
	FRESNEL_KHRONOS_REF=$(abspath $(BUILD))/khronos-ref $(BUILD)/bin/fresnel-bench
	bench/trace_bench.sh $(BUILD)/bin/fresnel
	python3 bench/batch_bench.py $(BUILD)/bin/fresnel $(CURDIR)/../shared
	python3 bench/python_bench.py $(BUILD)/bin/fresnel $(BUILD) $(CURDIR)/../shared
	python3 bench/scaling_bench.py $(BUILD)/bin/fresnel $(CURDIR)/../shared

# Optional, not part of `make test`: raster vs `fresnel trace` per shared model x environment
# (~10 min on 2 cores); writes docs/fidelity/ and the README's fidelity-report section. Then
# --ao off/baked against Blender Cycles (Debian's blender; its images made once, ~8 min), and
# the shadow scenes against Cycles (~3.5 min; its images made once, ~3.5 min more).
fidelity-report: configure
	cmake --build $(BUILD) -j $(JOBS) --target fresnel
	bench/fidelity_report.py $(BUILD)/bin/fresnel --readme docs/fidelity.md
	python3 bench/occlusion_fidelity.py $(BUILD)/bin/fresnel
	python3 bench/shadow_fidelity.py $(BUILD)/bin/fresnel

# Optional, not part of `make test`: OBJ -> glTF against obj2gltf (npm 3.2.0, installed into
# $(BUILD)/node-tools), under the one OpenGL 1 light (bench/peer-report.sh, ~1 min) and under
# the studio environment (bench/peer_report_ibl.py, ~9 min); rewrites bench/peer-report*.md.
peer-report: configure
	cmake --build $(BUILD) -j $(JOBS) --target fresnel fresnel_python
	@[ -x $(BUILD)/node-tools/node_modules/.bin/obj2gltf ] || \
	  (mkdir -p $(BUILD)/node-tools && cd $(BUILD)/node-tools && npm install --no-save obj2gltf@3.2.0)
	bench/peer-report.sh $(BUILD) $(BUILD)/peer-report && cp $(BUILD)/peer-report/peer-report.md bench/peer-report.md
	/usr/bin/python3 bench/peer_report_ibl.py --build $(BUILD) --report bench/peer-report-ibl.md

# The web page: the same libraries through Debian's Emscripten on WebGL 2, into $(WEB_BUILD)/
# (index.html, fresnel.js, fresnel.wasm; serve the folder with any static server). Debian's
# Emscripten ships its system libraries prebuilt in a frozen cache (/usr/share/emscripten/cache,
# read only), so nothing is cached outside the build folder. NODE_PATH: its JavaScript tools'
# modules when the `node` on PATH is not Debian's; EMSDK_PYTHON: Debian's Python.
WEB_ENV := NODE_PATH=/usr/share/nodejs EMSDK_PYTHON=/usr/bin/python3
web-deps:
	@scripts/install-deps.sh scripts/web-packages.txt

web: web-deps
	@test -f $(WEB_BUILD)/CMakeCache.txt || $(WEB_ENV) emcmake cmake -S . -B $(WEB_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release
	$(WEB_ENV) cmake --build $(WEB_BUILD) -j $(JOBS)
	@echo "the page is in $(WEB_BUILD)/ (e.g. python3 -m http.server -d $(WEB_BUILD), then open http://localhost:8000/)"

# The page's size and speed against the Khronos Sample Renderer in the same browser (printed, not asserted).
web-bench: web
	@scripts/install-test-tools.sh $(BUILD)/node-tools
	@scripts/setup-khronos-ref.sh $(BUILD)/khronos-ref
	node bench/web_bench.mjs $(WEB_BUILD) $(CURDIR)/../shared $(BUILD)/node-tools $(BUILD)/khronos-ref

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) build-fuzz $(WEB_BUILD)
