# stiction — static friction of hard-coated rough surfaces.
# Targets: all (default), deps, demo, check, fuzz, validate, bench, reproduce, install,
# clean.
# O=DIR puts every build product under DIR (default: the source tree).
# SANITIZE=1 builds with AddressSanitizer + UndefinedBehaviorSanitizer (default O=build-san).

VERSION   := 0.1.0
PREFIX    ?= /usr/local
ifeq ($(SANITIZE),1)
O         ?= build-san
else
O         ?= .
endif

CC        ?= cc
# A build runs on all cores unless told otherwise (make -jN or JOBS=N); with
# more than one goal on the command line (make clean all, make check bench)
# the goals would run at once, so then only as told.  A make started by a
# recipe shares its parent's jobs.
JOBS      ?= $(shell nproc 2>/dev/null || echo 1)
ifeq ($(MAKELEVEL)$(filter-out 0 1,$(words $(MAKECMDGOALS))),0)
MAKEFLAGS += -j$(JOBS)
endif
# Open MPI: one binary; MPI is initialised only under mpirun -n N > 1
# (asperity/table_mpi.c)
PKGS      := fftw3 hdf5 inih ompi-c
OPTFLAGS  ?= -O2
CSTD      := -std=c11 -D_DEFAULT_SOURCE
WARN      := -Wall -Wextra -Werror
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
CPPFLAGS  += -I/usr/include/suitesparse -DSTC_VERSION='"$(VERSION)"'
CFLAGS    += $(CSTD) $(OPTFLAGS) $(WARN) -fopenmp -fPIC $(PKG_CFLAGS)
# GSL's CBLAS calls are served by OpenBLAS (no -lgslcblas: one CBLAS only)
LDLIBS    += -lgsl -lfftw3_omp $(PKG_LIBS) -lcholmod -lopenblas -lpng -lm
LDFLAGS   += -fopenmp
ifeq ($(SANITIZE),1)
CFLAGS    += -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
LDFLAGS   += -fsanitize=address,undefined
endif

# Layers: core/ (status, checks, parsing, HDF5 attributes) under asperity/
# (one asperity, friction tables) and surface/ (rough surfaces, GW sums; it
# uses the asperity models through include/stiction/model.h and table.h);
# the CLI (tools/cli/) on top.  Each layer is compiled seeing the public
# headers and its own private ones only; the tests are unit tests of the
# internals and see every private folder.
INC_core     := -Iinclude -Icore
INC_asperity := $(INC_core) -Iasperity
INC_surface  := $(INC_core) -Isurface
INC_cli      := -Iinclude -Itools/cli
INC_tests    := $(INC_core) -Iasperity -Isurface -Itests

LIB_SRC   := $(sort $(wildcard core/*.c asperity/*.c surface/*.c))
CLI_SRC   := $(sort $(wildcard tools/cli/*.c))
TEST_SRC  := $(sort $(wildcard tests/test_*.c))
LIB_OBJ   := $(LIB_SRC:%.c=$(O)/obj/%.o)
CLI_OBJ   := $(CLI_SRC:%.c=$(O)/obj/%.o)
# make check runs the test programs on every core (tools/run-tests.sh), the
# longest first (their order here: measured wall times, longest first)
TEST_LONG := $(filter $(TEST_SRC:tests/%.c=%),test_shear test_cli_table test_solver \
             test_table_mpi test_table test_cli test_cli_asperity)
TEST_BIN  := $(TEST_LONG:%=$(O)/tests-bin/%) \
             $(filter-out $(TEST_LONG:%=$(O)/tests-bin/%),$(TEST_SRC:tests/%.c=$(O)/tests-bin/%))
HEADERS   := $(wildcard include/stiction/*.h)

STATIC    := $(O)/lib/libstiction.a
SHARED    := $(O)/lib/libstiction.so
CLI       := $(O)/bin/stiction
DEPSTAMP  := $(O)/obj/.deps-ok

.PHONY: all deps demo check fuzz tables validate bench reproduce install clean
.DELETE_ON_ERROR:

all: $(STATIC) $(SHARED) $(CLI)

# A build that finds a Debian package missing installs it (make deps) first;
# a changed package list is checked again.
$(DEPSTAMP): tools/deps.sh
	@mkdir -p $(@D)
	@tools/deps.sh check || $(MAKE) --no-print-directory deps
	@tools/deps.sh check
	@touch $@

deps:
	@tools/deps.sh install

# The commit a build comes from, for `stiction --version` (compiled into the
# CLI's main.c only, rebuilt when it changes), so results made with an older
# binary name the code that made them
COMMIT := $(shell [ "$$(git -C $(CURDIR) rev-parse --show-toplevel 2>/dev/null)" = "$(CURDIR)" ] \
                  && git -C $(CURDIR) describe --always --dirty 2>/dev/null)
COMMIT_STAMP := $(O)/obj/.commit
$(COMMIT_STAMP): FORCE
	@mkdir -p $(@D)
	@echo '$(COMMIT)' | cmp -s - $@ || echo '$(COMMIT)' > $@
$(O)/obj/tools/cli/main.o: $(COMMIT_STAMP)
ifneq ($(COMMIT),)
$(O)/obj/tools/cli/main.o: CPPFLAGS += -DSTC_COMMIT='"$(COMMIT)"'
endif
.PHONY: FORCE

$(O)/obj/%.o: %.c | $(DEPSTAMP)
	@mkdir -p $(@D)
	$(CC) $(LAYER_INC) $(CPPFLAGS) $(CFLAGS) $(LAYER_CFLAGS) -MMD -MP -c $< -o $@

$(O)/obj/core/%.o:      LAYER_INC = $(INC_core)
$(O)/obj/asperity/%.o:  LAYER_INC = $(INC_asperity)
$(O)/obj/surface/%.o:   LAYER_INC = $(INC_surface)
$(O)/obj/tools/cli/%.o: LAYER_INC = $(INC_cli)
# The shared library exports the STC_API functions of include/stiction/ only
# (include/stiction/export.h); the static library keeps every symbol.
$(O)/obj/core/%.o $(O)/obj/asperity/%.o $(O)/obj/surface/%.o: LAYER_CFLAGS = -fvisibility=hidden

# The element kernels dominate FE assembly; -O3 (vectorised loops) makes them
# about 1.8x faster (measured: hex8 force + stiffness 12.2 us -> 6.8 us).
ifneq ($(SANITIZE),1)
$(O)/obj/asperity/elem.o: OPTFLAGS = -O3
endif

$(STATIC): $(LIB_OBJ)
	@mkdir -p $(@D)
	rm -f $@
	ar rcs $@ $^

$(SHARED): $(LIB_OBJ)
	@mkdir -p $(@D)
	$(CC) -shared $(LDFLAGS) -Wl,-soname,libstiction.so.0 -o $@ $^ $(LDLIBS)

$(CLI): $(CLI_OBJ) $(STATIC)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(STATIC) $(LDLIBS)

$(O)/tests-bin/%: tests/%.c $(STATIC) $(HEADERS) $(wildcard tests/*.h) | $(DEPSTAMP)
	@mkdir -p $(@D)
	$(CC) $(INC_tests) $(CPPFLAGS) -DSTC_DATA_DIR='"$(CURDIR)/data"' $(CFLAGS) -o $@ $< $(STATIC) \
	    -lcmocka $(LDFLAGS) $(LDLIBS)

check: all $(TEST_BIN)
	@STC_SHARED=$(SHARED) STC_CC='$(CC)' STICTION_CLI=$(abspath $(CLI)) tools/run-tests.sh $(TEST_BIN) tools/check-exports.sh

# The randomised input tests of make check, FUZZ_CASES times as many cases.
FUZZ_CASES ?= 100
fuzz: all $(O)/tests-bin/test_fuzz
	@STICTION_FUZZ_CASES=$(FUZZ_CASES) tools/run-tests.sh $(O)/tests-bin/test_fuzz

demo: all
	@tools/demo.sh $(CLI)

tables: all
	@tools/tables.sh $(CLI) $(TABLES)

# + : a part runs make install (tools/validate.d/05-install.sh) on the jobserver
validate: all
	+@st=0; ONLY=$(ONLY) tools/fragments.sh validate $(CLI) || st=$$?; \
	python3 tools/validate-report.py results docs/validation.md; exit $$st

bench: all
	@ONLY=$(ONLY) tools/fragments.sh bench $(CLI)

reproduce: all
	@ONLY=$(ONLY) tools/fragments.sh reproduce $(CLI)

install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/stiction \
	    $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 $(STATIC) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(SHARED) $(DESTDIR)$(PREFIX)/lib/libstiction.so.$(VERSION)
	ln -sf libstiction.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/libstiction.so.0
	ln -sf libstiction.so.0 $(DESTDIR)$(PREFIX)/lib/libstiction.so
	install -m 644 include/stiction/*.h $(DESTDIR)$(PREFIX)/include/stiction/
	install -m 755 $(CLI) $(DESTDIR)$(PREFIX)/bin/
	for d in data/*/; do \
	    install -d $(DESTDIR)$(PREFIX)/share/stiction/$$d && \
	    for f in $$d*.csv $$d*.h5; do \
	        [ ! -e "$$f" ] || install -m 644 "$$f" $(DESTDIR)$(PREFIX)/share/stiction/$$d || exit 1; \
	    done; \
	done
	install -m 644 data/README.md $(DESTDIR)$(PREFIX)/share/stiction/data/
	sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(VERSION)|g' \
	    -e 's|@LIBS@|$(LDLIBS)|g' tools/stiction.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/stiction.pc

clean:
	rm -rf $(O)/obj $(O)/lib $(O)/bin $(O)/tests-bin build-san

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d)
