# What every engine example's Makefile shares. An engine's Makefile sets ENGINE (its program is
# decal_$(ENGINE), from decal_$(ENGINE).cpp), ENGINE_CFLAGS, ENGINE_LIBS and RUNS (the argument
# lists to run it with, one per run, `,` between words, `-` for none), then includes this file.
#   make check    build, then run under Xvfb (pictures in target/engines)
# The library must exist first: `cargo build --release --lib` (or set ZSHIFT_LIBDIR).
ROOT          := ../../..
ZSHIFT_LIBDIR ?= $(ROOT)/target/release
BUILD         ?= $(ROOT)/target/engines
CXX           ?= c++
CXXFLAGS      ?= -std=c++17 -O2 -Wall -Wextra -Werror
CPPFLAGS      += -I$(ROOT)/include
ZSHIFT_LIBS   := -L$(ZSHIFT_LIBDIR) -Wl,-rpath,$(abspath $(ZSHIFT_LIBDIR)) -lzshift
# Fails, not skips, when Xvfb or the engine is missing.
XVFB          := xvfb-run -a -s '-screen 0 1024x768x24'
PROGRAM       := $(BUILD)/decal_$(ENGINE)

.PHONY: all check clean
all: $(PROGRAM)

$(PROGRAM): decal_$(ENGINE).cpp ../common/decal_scene.h $(ROOT)/include/zshift.h | $(BUILD)
	$(CXX) $(CPPFLAGS) $(ENGINE_CFLAGS) $(CXXFLAGS) -o $@ $< $(ZSHIFT_LIBS) $(ENGINE_LIBS) -lGL

$(BUILD):
	mkdir -p $@

check: all
	rm -f $(BUILD)/$(ENGINE)_*.png
	$(foreach run,$(RUNS),$(XVFB) $(PROGRAM) $(if $(filter -,$(run)),,$(subst $(comma), ,$(run))) $(BUILD) &&) true

comma := ,

clean:
	rm -f $(PROGRAM)
