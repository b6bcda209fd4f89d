# splinecast — build, test and demo. `make demo` and `make test` are the
# whole set-up on a fresh Debian 12 machine (as root): both install missing
# Debian packages through `make deps` first.
#
# BUILD selects the build folder (several can coexist: `make BUILD=build-x`);
# `make asan` builds into build-asan with AddressSanitizer and UBSan.

BUILD   ?= build
CC      ?= cc
OPT     ?= -O2
SAN     ?=
CFLAGS  ?= $(OPT) -g
CFLAGS  += -std=c11 -Wall -Wextra -Wshadow -Wno-unused-parameter -MMD -MP \
           -D_DEFAULT_SOURCE $(INC) $(SAN)
LDFLAGS += $(SAN)

GLSLANG_LIBS = -lglslang -lSPIRV -lMachineIndependent -lOSDependent -lGenericCodeGen \
               -lOGLCompiler -lglslang-default-resource-limits -lSPIRV-Tools-opt \
               -lSPIRV-Tools -lstdc++
LIBS    = -lpng -lqhull_r $(GLSLANG_LIBS) -lEGL -ldl -lpthread -lm

# Debian packages the project needs to build, test and demo.
DEB_PACKAGES = build-essential pkg-config libpng-dev libqhull-dev glslang-dev glslang-tools \
               libosmesa6-dev libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri \
               libglu1-mesa-dev khronos-api gnuplot-nox occt-misc clang-14 libclang-rt-14-dev \
               libglfw3-dev xvfb xauth libocct-data-exchange-dev libocct-modeling-algorithms-dev

# The layers, lowest first (docs/README.md). Each folder is compiled with the
# include paths of the layers it may use and no others, so that a header
# included across a layer it must not see is a compile error: gen/ sees
# only gen/, gen/base/ and gen/include/; the runtime's folders see the
# folders below them; only the tests see everything. The public headers are
# alone in gen/include/ (status, errors, logging, option enums) and
# runtime/include/ (splinecast.h), so that what sees only them sees nothing
# internal.
INC_PUBLIC    = -Iruntime/include -Igen/include
INC_BASE      = -Igen/include -Igen/base
INC_GEN       = -Igen $(INC_BASE)
INC_MODEL     = -Iruntime/model $(INC_BASE)
INC_IO        = -Iruntime/io $(INC_MODEL)
INC_TERRAIN   = -Iruntime/terrain $(INC_MODEL)
INC_PREPARE   = -Iruntime/prepare -Iruntime/terrain $(INC_MODEL) $(INC_GEN)
INC_REFERENCE = -Iruntime/reference -Iruntime/terrain $(INC_IO)
INC_GL        = -Iruntime/gl -I$(BUILD) -Iruntime/reference -Iruntime/prepare -Iruntime/terrain $(INC_IO) $(INC_GEN)
INC_API       = -Iruntime -Iruntime/include $(INC_GL)
$(BUILD)/gen/base/%.o:          INC = $(INC_BASE)
$(BUILD)/gen/%.o:               INC = $(INC_GEN)
$(BUILD)/embedded_templates.o:  INC = $(INC_BASE)
$(BUILD)/embedded_scenes.o:     INC = $(INC_BASE)
$(BUILD)/runtime/model/%.o:     INC = $(INC_MODEL)
$(BUILD)/runtime/io/%.o:        INC = $(INC_IO)
$(BUILD)/runtime/terrain/%.o:   INC = $(INC_TERRAIN)
$(BUILD)/runtime/prepare/%.o:   INC = $(INC_PREPARE)
$(BUILD)/runtime/reference/%.o: INC = $(INC_REFERENCE)
$(BUILD)/runtime/gl/%.o:        INC = $(INC_GL)
$(BUILD)/runtime/%.o:           INC = $(INC_API)
# The command line and the example programs use the library as any program
# would: they see only the paths of the installed headers (splinecast.h and
# the two it includes), so that a use of an internal header is a compile
# error. One program measures internals no public call reaches and still
# sees everything: the compiler benchmark (IR sizes and pass times).
$(BUILD)/examples/%.o:          INC = $(INC_PUBLIC)
INTERNAL_EXAMPLES = examples/bench_compiler.c
$(patsubst %.c,$(BUILD)/%.o,$(INTERNAL_EXAMPLES)): INC = $(INC_API)
$(BUILD)/tests/%.o:             INC = $(INC_API) -Iruntime/terrain -Itests -Iexamples/splinecast

RUNTIME_SRC  = $(wildcard runtime/*.c runtime/*/*.c)
GEN_SRC      = $(wildcard gen/*.c gen/base/*.c)
CLI_SRC      = $(wildcard examples/splinecast/*.c)
TEST_SRC     = $(wildcard tests/*.c)
TEMPLATE_FILES = $(wildcard templates/*)
SCENE_FILES  = examples/scenes/teapot32.bpt

LIB_OBJ  = $(patsubst %.c,$(BUILD)/%.o,$(RUNTIME_SRC) $(GEN_SRC)) \
           $(BUILD)/embedded_templates.o $(BUILD)/embedded_scenes.o
CLI_OBJ  = $(patsubst %.c,$(BUILD)/%.o,$(CLI_SRC))
# The tests also check the command line's spellings of the options and
# its file names, and run the stability suite as `bench --stability` does.
TEST_OBJ = $(patsubst %.c,$(BUILD)/%.o,$(TEST_SRC)) $(BUILD)/examples/splinecast/options.o \
           $(BUILD)/examples/splinecast/cli.o $(BUILD)/examples/splinecast/stability.o

# STEP files through Open CASCADE (docs/step.md): its part
# (runtime/io/step_occt.cpp) is built when its headers and libraries are
# found (`make deps` installs them); without them reading a .stp/.step file
# fails with "built without STEP support". HAVE_OCCT=0 builds without.
CXX       ?= g++
OCCT_INC  ?= /usr/include/opencascade
HAVE_OCCT ?= $(shell test -f $(OCCT_INC)/STEPCAFControl_Reader.hxx && \
               test -f "$$($(CXX) -print-file-name=libTKXDESTEP.so)" && echo 1)
OCCT_LIBS = -lTKXDESTEP -lTKXDEIGES -lTKXCAF -lTKSTEP -lTKIGES -lTKXSBase -lTKVCAF -lTKCAF \
            -lTKLCAF -lTKCDF -lTKBool -lTKShHealing -lTKTopAlgo -lTKGeomAlgo -lTKBRep \
            -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel -lstdc++
CXXFLAGS  ?= $(OPT) -g
CXXFLAGS  += -std=c++17 -Wall -Wextra -Wno-unused-parameter -MMD -MP $(INC) -isystem $(OCCT_INC) \
             $(SAN)
ifeq ($(HAVE_OCCT),1)
CFLAGS   += -DSC_HAVE_OCCT
LIB_OBJ  += $(BUILD)/runtime/io/step_occt.o
LIBS     += $(OCCT_LIBS)
endif

# What the objects are compiled and linked with, in a file rewritten only
# when that changes: a build after `make deps` installed Open CASCADE (or
# with other flags) recompiles everything, instead of linking objects made
# without it.
CONFIG_STAMP := $(BUILD)/config.stamp
CONFIG_TEXT  := $(CC) $(CFLAGS) | $(CXX) $(CXXFLAGS) | $(LIBS)
$(shell mkdir -p $(BUILD) && { printf '%s\n' '$(CONFIG_TEXT)' | cmp -s - $(CONFIG_STAMP) || \
        printf '%s\n' '$(CONFIG_TEXT)' > $(CONFIG_STAMP); })

$(BUILD)/%.o: %.cpp $(CONFIG_STAMP)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -c $< -o $@

LIB  = $(BUILD)/libsplinecast.a
CLI  = $(BUILD)/splinecast
TESTS = $(BUILD)/run_tests

.PHONY: all deps demo test asan fuzz fuzz-smoke check-big clean install uninstall
all: $(CLI) $(TESTS) $(BUILD)/viewer

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do \
	    dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; \
	  done); \
	if [ -n "$$missing" ]; then \
	  echo "deps: installing" $$missing; \
	  if [ "$$(id -u)" != 0 ]; then echo "deps: run as root (apt-get) to install:" $$missing >&2; exit 1; fi; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	else echo "deps: all Debian packages present"; fi

$(BUILD)/%.o: %.c $(CONFIG_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

# Files compiled into the library, so that it needs no data directory: the
# GLSL templates (the compiler's table) and the default scene (the
# runtime's).
$(BUILD)/embedded_templates.c: gen/base/embed.sh $(TEMPLATE_FILES) Makefile
	@mkdir -p $(BUILD)
	sh gen/base/embed.sh scg_embedded_templates $(TEMPLATE_FILES) > $@.tmp && mv $@.tmp $@
$(BUILD)/embedded_scenes.c: gen/base/embed.sh $(SCENE_FILES) Makefile
	@mkdir -p $(BUILD)
	sh gen/base/embed.sh sc_embedded_scenes $(SCENE_FILES) > $@.tmp && mv $@.tmp $@

$(BUILD)/embedded_%.o: $(BUILD)/embedded_%.c
	$(CC) $(CFLAGS) -c $< -o $@

# The GL function table of runtime/gl/gl_loader.h, generated from the Khronos
# registry's core-profile header (Debian: libgl-dev / khronos-api).
GL_REGISTRY_HEADER = /usr/include/GL/glcorearb.h
$(BUILD)/gl_functions.h: runtime/gl/gl_functions.awk $(GL_REGISTRY_HEADER)
	@mkdir -p $(BUILD)
	awk -v MAX=4.5 -f runtime/gl/gl_functions.awk $(GL_REGISTRY_HEADER) > $@.tmp && mv $@.tmp $@

$(LIB_OBJ) $(CLI_OBJ) $(TEST_OBJ): | $(BUILD)/gl_functions.h

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(CLI): $(CLI_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LIBS)

# The test list: one X(name) per line starting with TEST( in tests/*.c.
# Remade every time (it is only rewritten when it changes), so that a test
# file removed or renamed leaves no stale entry behind.
.PHONY: FORCE
$(BUILD)/tests_list.h: FORCE
	@mkdir -p $(BUILD)
	@grep -h '^TEST(' $(TEST_SRC) | sed 's/^TEST(\([A-Za-z0-9_]*\)).*/X(\1)/' > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@; rm -f $@.tmp

$(BUILD)/tests/main.o: $(BUILD)/tests_list.h

$(TESTS): $(TEST_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -o $@ $(TEST_OBJ) $(LIB) $(LIBS)

# demo.sh runs deps and the build itself, so that it can time them.
demo:
	@sh examples/demo.sh $(CLI) $(BUILD)/demo $(MAKE) --no-print-directory BUILD=$(BUILD)

test: deps
	@$(MAKE) --no-print-directory all
	@SC_CLI=$(CLI) SC_BUILD=$(BUILD) LP_NUM_THREADS=2 $(TESTS) $(T)

# Mesa and LLVM leak on their own: their reports are suppressed by name.
asan:
	@$(MAKE) --no-print-directory BUILD=build-asan OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" test \
	  ASAN_OPTIONS=abort_on_error=0 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp

# Fuzz targets (tests/fuzz/fuzz_*.c, docs/limits.md): the scene readers, the
# AOV reader and the key parser under clang's libFuzzer with ASan and UBSan,
# linked with only the layers they read through. `make fuzz-smoke` runs each
# for FUZZ_SECONDS on its corpus (tests/fuzz/corpus/NAME, kept minimised),
# writing new inputs to a scratch folder, never into the tree.
FUZZ_BUILD   = build-fuzz
FUZZ_CC      ?= clang-14
FUZZ_SECONDS ?= 20
FUZZ_NAMES   = $(patsubst tests/fuzz/fuzz_%.c,%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_LIB_SRC = $(wildcard gen/base/*.c runtime/model/*.c runtime/io/*.c) gen/key.c \
               runtime/terrain/heights.c
FUZZ_LIB_OBJ = $(patsubst %.c,$(BUILD)/%.o,$(FUZZ_LIB_SRC)) $(BUILD)/embedded_scenes.o
# With Open CASCADE the readers' targets reach it through the STEP reader
# (fuzz_step fuzzes the pre-scan and, behind it, the library).
FUZZ_CXX     ?= clang++-14
FUZZ_LIBS    = -lpng -lm
FUZZ_LINK    = $(CC)
ifeq ($(HAVE_OCCT),1)
FUZZ_LIB_OBJ += $(BUILD)/runtime/io/step_occt.o
FUZZ_LIBS    += $(OCCT_LIBS)
FUZZ_LINK    = $(CXX)
endif
FUZZ_SAN     = -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined \
               -fno-omit-frame-pointer
$(BUILD)/tests/fuzz/%.o: INC = $(INC_IO) $(INC_GEN) -Iruntime/terrain
.PRECIOUS: $(BUILD)/tests/fuzz/%.o
fuzz: deps
	@command -v $(FUZZ_CC) >/dev/null || { echo "fuzz: $(FUZZ_CC) is missing (make deps)" >&2; exit 1; }
	@$(MAKE) --no-print-directory BUILD=$(FUZZ_BUILD) CC=$(FUZZ_CC) CXX=$(FUZZ_CXX) OPT=-O1 SAN="$(FUZZ_SAN)" \
	  $(patsubst %,$(FUZZ_BUILD)/fuzz_%,$(FUZZ_NAMES))
$(BUILD)/fuzz_%: $(BUILD)/tests/fuzz/fuzz_%.o $(FUZZ_LIB_OBJ)
	$(FUZZ_LINK) $(LDFLAGS) -fsanitize=fuzzer -o $@ $^ $(FUZZ_LIBS)
fuzz-smoke: fuzz
	@for n in $(FUZZ_NAMES); do \
	  scratch=$$(mktemp -d) && \
	  echo "fuzz-smoke: $$n ($(FUZZ_SECONDS) s)" && \
	  $(FUZZ_BUILD)/fuzz_$$n -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=1024 -timeout=10 \
	    -print_final_stats=1 $$scratch tests/fuzz/corpus/$$n 2>$$scratch.log; \
	  status=$$?; grep -E "^#[0-9]+" $$scratch.log | tail -1 | cut -c1-100; \
	  grep "stat::number_of_executed_units" $$scratch.log; \
	  rm -rf $$scratch; \
	  if [ $$status != 0 ]; then tail -40 $$scratch.log; rm -f $$scratch.log; exit 1; fi; \
	  rm -f $$scratch.log; \
	done

# The large real work the envelope must admit (docs/limits.md): 100,000
# bicubic patches, 1.6 M control points, read by the command line.
.PHONY: check-big
check-big: $(CLI)
	@sh tests/big_scene.sh $(BUILD)/big.obj
	@start=$$(date +%s.%N); \
	first=$$($(CLI) info $(BUILD)/big.obj | head -1); \
	echo "check-big: $$first in $$(awk "BEGIN { print $$(date +%s.%N) - $$start }") s"; \
	rm -f $(BUILD)/big.obj; test "$$first" = "surfaces 100000"

clean:
	rm -rf build build-asan $(FUZZ_BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

# Compiler figures (docs/compiler.md): IR sizes and build/optimise/interpret
# times per key.
.PHONY: bench-compiler
bench-compiler: $(BUILD)/bench_compiler
$(BUILD)/bench_compiler: $(BUILD)/examples/bench_compiler.o $(LIB)
	$(CC) $(LDFLAGS) -o $@ $< $(LIB) $(LIBS)

# GLSL for the variant keys of every example scene, generated and validated
# by glslang at build time (a rejected program fails the build).
.PHONY: shaders bless
SHADER_SCENES = $(wildcard examples/scenes/*.bpt examples/scenes/*.obj examples/scenes/*.igs)
shaders: $(CLI)
	@failed=0; for s in $(SHADER_SCENES); do \
	  $(CLI) gen --scene $$s -o $(BUILD)/shaders/$$(basename $$s | sed 's/\.[^.]*$$//') \
	    || failed=$$((failed+1)); \
	done; test $$failed = 0 || { echo "shaders: $$failed scene(s) failed" >&2; exit 1; }

# Regenerates the golden GLSL files of tests/golden/ after an intended change.
bless: $(CLI)
	@sh tests/bless.sh $(CLI)

# The generated GLSL must not depend on the C compiler that built splinecast
# (docs/compiler.md): a clang build must reproduce the goldens of a gcc build.
.PHONY: check-clang
check-clang:
	@$(MAKE) --no-print-directory BUILD=$(BUILD)-clang CC=clang test T=emit_golden_files

# Installation (docs/api.md): the static library, the public header, the
# command line and a pkg-config file. The .pc is written straight into the
# staging tree so that it always carries this PREFIX; its Libs name every
# library libsplinecast.a needs, since the archive is static and Debian's
# glslang.pc does not link.
PREFIX  ?= /usr/local
DESTDIR ?=
SPLINECAST_VERSION = $(shell sed -n 's/^\#define SPLINECAST_VERSION "\(.*\)"/\1/p' runtime/include/splinecast.h)
install: $(LIB) $(CLI)
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/bin
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/libsplinecast.a
	install -m 644 runtime/include/splinecast.h gen/include/splinecast_base.h gen/include/splinecast_options.h \
	  $(DESTDIR)$(PREFIX)/include/
	install -m 755 $(CLI) $(DESTDIR)$(PREFIX)/bin/splinecast
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(SPLINECAST_VERSION)|' \
	    -e 's|@LIBS@|$(LIBS)|' runtime/splinecast.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/splinecast.pc.tmp
	mv $(DESTDIR)$(PREFIX)/lib/pkgconfig/splinecast.pc.tmp $(DESTDIR)$(PREFIX)/lib/pkgconfig/splinecast.pc

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/lib/libsplinecast.a $(DESTDIR)$(PREFIX)/include/splinecast.h \
	  $(DESTDIR)$(PREFIX)/include/splinecast_base.h $(DESTDIR)$(PREFIX)/include/splinecast_options.h \
	  $(DESTDIR)$(PREFIX)/bin/splinecast $(DESTDIR)$(PREFIX)/lib/pkgconfig/splinecast.pc

# The interactive viewer (examples/viewer, docs/api.md): a GLFW window that
# shows the library's frames; public API only. Its test runs it under Xvfb.
VIEWER_LIBS = -lglfw -lGL -lpng
$(BUILD)/viewer: $(BUILD)/examples/viewer/viewer.o $(LIB)
	$(CC) $(LDFLAGS) -o $@ $< $(LIB) $(LIBS) $(VIEWER_LIBS)

# GLU's tessellator alone (docs/chart.md): the check that the chart's
# glu-TOL rows time GLU as a program of its own would. Links libGLU, which
# the library itself only opens at run time.
.PHONY: glu-tessellate
glu-tessellate: $(BUILD)/glu_tessellate
$(BUILD)/glu_tessellate: examples/glu_tessellate.c
	@mkdir -p $(BUILD)
	$(CC) $(OPT) -std=c11 -Wall -Wextra -D_DEFAULT_SOURCE -o $@ $< -lGLU -lm

# The real-file survey (docs/step.md, docs/iges.md): Open CASCADE's sample
# shapes written as STEP and IGES by tests/survey/occt_convert.cpp (a tool,
# not part of the library; built only with Open CASCADE), then `splinecast
# info` on them and on the shared files, 60 s cap each. SURVEY_RENDER=K
# also renders every K-th file against the reference at 256x256.
OCC_SHAPES ?= /usr/share/opencascade/data/occ
SURVEY_DIR  = $(BUILD)/survey
SURVEY_DATA ?= $(SC_DATA_DIR) /usr/share/opencascade/data/iges /usr/share/opencascade/data/step
SC_DATA_DIR ?= ../shared/data
.PHONY: survey
ifeq ($(HAVE_OCCT),1)
survey: $(CLI) $(BUILD)/occt_convert
	@mkdir -p $(SURVEY_DIR)
	@for f in $(OCC_SHAPES)/*.brep $(OCC_SHAPES)/*.rle; do \
	    [ -f "$$f" ] && $(BUILD)/occt_convert "$$f" $(SURVEY_DIR) > /dev/null; done; true
	tests/survey/survey.sh $(CLI) $(SURVEY_DIR) $(wildcard $(SURVEY_DATA))
$(BUILD)/occt_convert: tests/survey/occt_convert.cpp
	@mkdir -p $(BUILD)
	$(CXX) $(OPT) -std=c++17 -Wall -Wextra -isystem $(OCCT_INC) -o $@ $< $(OCCT_LIBS)
else
survey:
	@echo "survey: needs Open CASCADE (make deps) to write its STEP and IGES files" >&2; exit 1
endif
