# CSF - build, test, install.
#
#   make            build build/csfc, build/csfvm, build/libcsfrt.a, build/csfview, and (but with SAN=1)
#                   libcsf.so and the Python package csf (make python)
#   make python     build/libcsf.so (runtime/api/csf_api.h) and the Python package in build/python/csf
#   make deps       install missing Debian packages (apt-get, as root)
#   make deps-chromium  headless Chromium, only for the browser test of csfview
#   make demo       deps + build + compile and run an example
#   make MPI=1      also build/csfvm-mpi, csfvm whose sweeps run across MPI ranks (make deps-mpi)
#   make check      every test, then the whole suite again under ASan/UBSan
#   make check-piles  the piles of balls of issue 28 (tests/piles/; not yet in make check)
#   make fuzz       the fuzz targets (clang, libFuzzer, ASan/UBSan) for FUZZ_SECONDS each
#                   (default 60); non-zero exit on a finding (tests/fuzz/README.md)
#   make deps-fuzz  install what make fuzz needs (clang, libfuzzer-14-dev)
#   make deps-editors  node, npm and vim (Debian), vscode-tmgrammar-test (npm, into BUILD/editors-deps):
#                   what the editors' test needs (tests/editors/; SKIP lines without them)
#   make bench      benchmarks; results under bench/results, summary in bench/README.md
#   make bench-peers  CSF beside SciPy's solve_ivp (installs python3-scipy: deps-peers)
#   make deps-cvode  libsundials-dev, only for make -C bench cvode (CVODE beside msbdf and bsimp)
#   make install    PREFIX=/usr/local DESTDIR=
#   make uninstall  the same PREFIX and DESTDIR: removes what install put there

PREFIX ?= /usr/local
DESTDIR ?=
BUILD ?= build
CC ?= cc
CFLAGS ?= -O2 -g
SAN ?=

DEB_PACKAGES = gcc make libgsl-dev check re2c bison pkg-config gnuplot-nox libhdf5-dev python3-h5py $(VIEW_PACKAGES) \
	$(PYTHON_PACKAGES) $(NOTEBOOK_PACKAGES)
# libhdf5-dev: -o RUN.h5 (serial HDF5, runtime/run/h5.c); python3-h5py: only for its test (SKIP without it)
# the Python package csf (python/csf: numpy, pandas optional) and its tests (pytest), for Debian's python3
PYTHON_PACKAGES = python3-numpy python3-pandas python3-pytest
# the notebooks of examples/ run through nbclient in a python3 kernel (tests/notebook/run.py; SKIP without them)
NOTEBOOK_PACKAGES = python3-nbclient python3-nbformat python3-ipykernel
PYTHON = /usr/bin/python3
# what csfview needs at run time: the JavaScript it inlines into its pages
# (gnuplot-nox, for its static plots, is above)
VIEW_PACKAGES = libjs-three libjs-dygraphs
# only for the browser test of csfview's page (tests/view/check.sh skips without it)
CHROMIUM_PACKAGES = chromium
PEER_PACKAGES = python3-scipy
CVODE_PACKAGES = libsundials-dev
BOX2D_PACKAGES = libbox2d-dev g++
# only for csfvm-mpi (make MPI=1) and its test (skipped without them)
MPI_PACKAGES = libopenmpi-dev openmpi-bin
MPI ?=
MPICC ?= mpicc
HAVE_MPICC := $(shell command -v $(MPICC) 2>/dev/null)
FUZZ_PACKAGES = clang libfuzzer-14-dev
# only for the test of editors/ (the TextMate grammar and the Vim files)
# (npm: Debian's package, unless the nodejs installed brings its own)
EDITOR_PACKAGES = nodejs vim $(if $(shell command -v npm 2>/dev/null),,npm)
TMGRAMMAR_TEST = vscode-tmgrammar-test@0.1.3
, := ,
SANFLAGS = $(if $(SAN),-fsanitize=address$(,)undefined$(,)float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer)
CSF_CFLAGS = -std=c11 -Wall -Wextra -ffp-contract=off -D_DEFAULT_SOURCE $(SANFLAGS)
CPPFLAGS_ALL = $(addprefix -I,$(RT_DIRS) $(CC_DIRS)) -I$(BUILD)
LDLIBS_GSL = $(shell pkg-config --libs gsl 2>/dev/null || echo -lgsl -lgslcblas) -lm
# serial HDF5, for runtime/run/h5.c alone
H5_CFLAGS = $(shell pkg-config --cflags hdf5-serial 2>/dev/null)
LDLIBS_H5 = $(strip $(shell pkg-config --libs hdf5-serial 2>/dev/null || echo -lhdf5))
# what a program that links libcsfrt.a links too
LDLIBS_RT = $(LDLIBS_H5) $(LDLIBS_GSL)
LDFLAGS_SAN = $(if $(SAN),-fsanitize=address$(,)undefined)

# The sources, by stage (README.md, "How the code is laid out"): every .c of
# compiler/ and runtime/ and of their folders is part of the compiler or of
# libcsfrt, but the programs' main files.
RT_DIRS = runtime $(patsubst %/,%,$(sort $(dir $(wildcard runtime/*/*.c))))
CC_DIRS = compiler $(patsubst %/,%,$(sort $(dir $(wildcard compiler/*/*.c compiler/*/*.y))))
# (and fmt_gen.c, run at build time: it writes the table of powers of ten of fmt.c)
RT_MAINS = runtime/tools/csfvm.c runtime/tools/sweep_mpi.c runtime/run/fmt_gen.c
RT_SRC = $(filter-out $(RT_MAINS),$(wildcard runtime/*.c runtime/*/*.c))
RT_H = $(wildcard runtime/*.h runtime/*/*.h) runtime/opcodes.def
RT_OBJ = $(RT_SRC:runtime/%.c=$(BUILD)/rt/%.o)
CC_SRC = $(filter-out compiler/main.c,$(wildcard compiler/*.c compiler/*/*.c))
CC_H = $(wildcard compiler/*.h compiler/*/*.h)
CC_GEN = $(BUILD)/lex.c $(BUILD)/parse.c
CC_OBJ = $(CC_SRC:compiler/%.c=$(BUILD)/cc/%.o) $(BUILD)/cc/lex.o $(BUILD)/cc/parse.o

all: $(BUILD)/csfc $(BUILD)/csfvm $(BUILD)/libcsfrt.a $(BUILD)/csfview $(if $(MPI),$(BUILD)/csfvm-mpi) \
	$(if $(SAN),,python)

$(BUILD)/rt/%.o: runtime/%.c $(RT_H)
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/rt/run/h5.o $(BUILD)/pic/run/h5.o: CPPFLAGS_ALL += $(H5_CFLAGS)
# csfc links a generated program with libcsfrt, GSL and these (compiler/back/cc.c)
$(BUILD)/cc/back/cc.o: CPPFLAGS_ALL += -DCSF_LDLIBS_H5='"$(LDLIBS_H5)"'

# fmt.c's table of powers of ten, computed exactly at build time (part of libcsfrt.a through fmt.o);
# the generator is built without CFLAGS and sanitizers: it runs here, whatever the library is for
$(BUILD)/fmt_gen: runtime/run/fmt_gen.c runtime/run/fmt_log.h
	@mkdir -p $(@D)
	$(CC) -std=c11 -Wall -Wextra -O1 -o $@ $<

$(BUILD)/fmt_pow10.h: $(BUILD)/fmt_gen
	$(BUILD)/fmt_gen >$@.tmp && mv $@.tmp $@

$(BUILD)/rt/run/fmt.o $(BUILD)/pic/run/fmt.o: $(BUILD)/fmt_pow10.h

$(BUILD)/libcsfrt.a: $(RT_OBJ)
	rm -f $@
	ar rcs $@ $^

# libcsf.so (runtime/api/csf_api.h): the runtime built position-independent, its API alone exported
# (runtime/api/csf_api.map: version node CSF_1). Not with SAN=1: a sanitized shared library needs the
# sanitizer's runtime loaded before it (tests/api_test.c drives the API under the sanitizers, linked
# with libcsfrt.a, which has runtime/api/api.c too).
SO_NAME = libcsf.so.1
PIC_OBJ = $(RT_SRC:runtime/%.c=$(BUILD)/pic/%.o)

$(BUILD)/pic/%.o: runtime/%.c $(RT_H)
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) -fPIC -fvisibility=hidden $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/$(SO_NAME): $(PIC_OBJ) runtime/api/csf_api.map
	$(CC) -shared -Wl,-soname,$(SO_NAME) -Wl,--version-script=runtime/api/csf_api.map -Wl,-z,defs -o $@ \
		$(PIC_OBJ) $(LDLIBS_RT)

$(BUILD)/libcsf.so: $(BUILD)/$(SO_NAME)
	ln -sf $(SO_NAME) $@

# the Python package csf: python/csf/*.py, and _paths.py, which says where it finds libcsf.so, csfc
# and csfvm (here: this build directory; make install writes the installed paths)
PY_SRC = $(wildcard python/csf/*.py)
PY_OUT = $(PY_SRC:python/%=$(BUILD)/python/%)
py_paths = printf '%s\n' '"""Where this copy of csf finds libcsf and the programs (written by make)."""' \
	'LIBCSF = "$(1)/$(SO_NAME)"' 'BINDIR = "$(2)"'

$(BUILD)/python/csf/%.py: python/csf/%.py
	@mkdir -p $(@D)
	cp $< $@

$(BUILD)/python/csf/_paths.py: Makefile
	@mkdir -p $(@D)
	$(call py_paths,$(abspath $(BUILD)),$(abspath $(BUILD))) >$@

python: $(BUILD)/libcsf.so $(PY_OUT) $(BUILD)/python/csf/_paths.py $(BUILD)/csfc $(BUILD)/csfvm

$(BUILD)/parse.c $(BUILD)/parse.h &: compiler/front/parse.y
	@mkdir -p $(BUILD)
	bison -Wall -Werror --defines=$(BUILD)/parse.h -o $(BUILD)/parse.c $<

$(BUILD)/lex.c: compiler/front/lex.re
	@mkdir -p $(BUILD)
	re2c -W -Werror -o $@ $<

$(BUILD)/cc/%.o: compiler/%.c $(CC_H) $(RT_H) $(BUILD)/parse.h
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/cc/%.o: $(BUILD)/%.c $(CC_H) $(RT_H) $(BUILD)/parse.h
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/csfc: $(CC_OBJ) $(BUILD)/cc/main.o $(BUILD)/libcsfrt.a
	$(CC) $(LDFLAGS_SAN) -o $@ $(CC_OBJ) $(BUILD)/cc/main.o $(BUILD)/libcsfrt.a $(LDLIBS_RT)

$(BUILD)/csfvm: $(BUILD)/rt/csfvm.o $(BUILD)/libcsfrt.a
	$(CC) $(LDFLAGS_SAN) -o $@ $^ $(LDLIBS_RT)

$(BUILD)/rt/csfvm.o: runtime/tools/csfvm.c $(RT_H)
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

# csfvm-mpi: csfvm with sweeps across MPI ranks; only this program needs MPI
$(BUILD)/csfvm-mpi: runtime/tools/sweep_mpi.c $(RT_H) $(BUILD)/libcsfrt.a
	$(MPICC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ $< $(BUILD)/libcsfrt.a $(LDLIBS_RT)

# csfview, a shell script: the in-tree copy reads its page template from viewer/
$(BUILD)/csfview: viewer/csfview.sh
	@mkdir -p $(@D)
	sed 's|@VIEWDIR@|$(CURDIR)/viewer|' $< >$@.tmp && chmod 755 $@.tmp && mv $@.tmp $@

# ---- tests ----

TEST_SRC = $(wildcard tests/unit/*.c)
TEST_OBJ = $(TEST_SRC:tests/unit/%.c=$(BUILD)/tests/%.o)
LDLIBS_CHECK = $(shell pkg-config --libs check 2>/dev/null || echo -lcheck -lsubunit -lrt -lpthread) -lm

$(BUILD)/tests/%.o: tests/unit/%.c tests/unit/*.h $(CC_H) $(RT_H) $(BUILD)/parse.h
	@mkdir -p $(@D)
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -Itests/unit -c $< -o $@

$(BUILD)/unit-tests: $(TEST_OBJ) $(CC_OBJ) $(BUILD)/libcsfrt.a
	$(CC) $(LDFLAGS_SAN) -o $@ $(TEST_OBJ) $(CC_OBJ) $(BUILD)/libcsfrt.a $(LDLIBS_CHECK) $(LDLIBS_RT)

$(BUILD)/fuzz-bytecode: tests/fuzz_bytecode.c $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ $< $(BUILD)/libcsfrt.a $(LDLIBS_RT)

# the sizes of a compiled program's code sections (tests/many/code_size.sh)
$(BUILD)/code-words: tests/code_words.c $(RT_H) $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ $< $(BUILD)/libcsfrt.a $(LDLIBS_RT)

# libcsf's API driven from C (tests/api_test.c), linked with libcsfrt.a: it runs under the sanitizers too
$(BUILD)/api-test: tests/api_test.c $(RT_H) $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ $< $(BUILD)/libcsfrt.a $(LDLIBS_RT)

# the fuzz targets (tests/fuzz/) replayed on the regression corpus by an ordinary main()
FUZZ_DEFS = -DCSF_FUZZ_STDLIB='"$(CURDIR)/stdlib"'

$(BUILD)/fuzz-replay-csfc: tests/fuzz/fuzz_csfc.c tests/fuzz/replay.c $(CC_OBJ) $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(FUZZ_DEFS) $(LDFLAGS_SAN) -o $@ tests/fuzz/fuzz_csfc.c \
		tests/fuzz/replay.c $(CC_OBJ) $(BUILD)/libcsfrt.a $(LDLIBS_RT)

$(BUILD)/fuzz-replay-csfb: tests/fuzz/fuzz_csfb.c tests/fuzz/replay.c $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ tests/fuzz/fuzz_csfb.c tests/fuzz/replay.c \
		$(BUILD)/libcsfrt.a $(LDLIBS_RT)

$(BUILD)/fuzz-replay-fmt: tests/fuzz/fuzz_fmt.c tests/fmt_ref.h tests/fuzz/replay.c $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ tests/fuzz/fuzz_fmt.c tests/fuzz/replay.c \
		$(BUILD)/libcsfrt.a $(LDLIBS_RT)

# csf_fmt_double against the snprintf/strtod loop it replaced, value by value (tests/fmt_double.c)
$(BUILD)/fmt-test: tests/fmt_double.c tests/fmt_ref.h $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(LDFLAGS_SAN) -o $@ $< $(BUILD)/libcsfrt.a $(LDLIBS_RT)

# the MPI sweep test runs where Open MPI is installed (tests/sweep/check.sh says SKIP otherwise)
# test-progs: what the tests run, built alone so that make check builds it nproc at a time
test-progs: all $(BUILD)/unit-tests $(BUILD)/fuzz-bytecode $(BUILD)/code-words $(BUILD)/fuzz-replay-csfc \
	$(BUILD)/fuzz-replay-csfb $(BUILD)/fuzz-replay-fmt $(BUILD)/fmt-test $(BUILD)/api-test $(if $(HAVE_MPICC),$(BUILD)/csfvm-mpi)

test: test-progs
	CSF_STDLIB=$(CURDIR)/stdlib $(BUILD)/unit-tests
	CSF_BUILD=$(BUILD) CSF_SAN=$(SAN) CFLAGS="$(CFLAGS) $(SANFLAGS)" sh tests/run.sh
	sh tests/layout/check.sh $(BUILD)

# the programs are built nproc at a time; tests/run.sh and tests/layout/check.sh run their
# tests nproc at a time too
NPROC := $(shell nproc 2>/dev/null || echo 2)
check:
	$(MAKE) -j$(NPROC) test-progs
	$(MAKE) test
	$(MAKE) -j$(NPROC) test-progs BUILD=build-san SAN=1 CFLAGS="-O1 -g"
	$(MAKE) test BUILD=build-san SAN=1 CFLAGS="-O1 -g"

# the piles of issue 28 (tests/piles/): not yet part of make check, since the
# contact solver they test is being rewritten; PILE_N limits the sizes (default "3 16 64");
# with a ball dropped onto two jammed between walls (tests/piles/jam.sh) and the Galton
# board of the issue, 100 balls through 10 rows (tests/piles/galton.sh)
check-piles: $(BUILD)/csfc $(BUILD)/csfvm
	@d=$$(mktemp -d) && st=0 && \
	sh tests/piles/statics.sh $(BUILD)/csfc $(BUILD)/csfvm "$$d" || st=1; \
	JAM_SPACINGS="0.0002 0.0007 0.001 0.002" sh tests/piles/jam.sh $(BUILD)/csfc $(BUILD)/csfvm "$$d" || st=1; \
	sh tests/piles/piles.sh $(BUILD)/csfc $(BUILD)/csfvm "$$d" || st=1; \
	sh tests/piles/galton.sh $(BUILD)/csfc $(BUILD)/csfvm "$$d" 100 10 || st=1; \
	rm -rf "$$d"; exit $$st

# ---- fuzzing (not part of make check: needs clang) ----
# make fuzz builds everything with clang, ASan, UBSan and libFuzzer's coverage in FUZZ_BUILD,
# then tests/fuzz/run.sh runs each target for FUZZ_SECONDS, one process at a time, at nice 19.

FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_CC ?= clang

$(BUILD)/fuzz-csfc: tests/fuzz/fuzz_csfc.c $(CC_OBJ) $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) $(FUZZ_DEFS) -fsanitize=fuzzer $(LDFLAGS_SAN) -o $@ $< \
		$(CC_OBJ) $(BUILD)/libcsfrt.a $(LDLIBS_RT)

$(BUILD)/fuzz-csfb: tests/fuzz/fuzz_csfb.c $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -fsanitize=fuzzer $(LDFLAGS_SAN) -o $@ $< \
		$(BUILD)/libcsfrt.a $(LDLIBS_RT)

$(BUILD)/fuzz-fmt: tests/fuzz/fuzz_fmt.c tests/fmt_ref.h $(BUILD)/libcsfrt.a
	$(CC) $(CSF_CFLAGS) $(CFLAGS) $(CPPFLAGS_ALL) -fsanitize=fuzzer $(LDFLAGS_SAN) -o $@ $< \
		$(BUILD)/libcsfrt.a $(LDLIBS_RT)

fuzz-targets: $(BUILD)/csfc $(BUILD)/fuzz-csfc $(BUILD)/fuzz-csfb $(BUILD)/fuzz-fmt

fuzz:
	$(MAKE) BUILD=$(FUZZ_BUILD) CC=$(FUZZ_CC) SAN=1 CFLAGS="-O1 -g -fsanitize=fuzzer-no-link" fuzz-targets
	sh tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# ---- set-up, demo, install ----

# $(call deb_install,TARGET,PACKAGES): install the missing Debian PACKAGES (as root)
deb_install = missing=""; for p in $(2); do \
		dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then echo "$(1): all present"; \
	elif [ "$$(id -u)" = 0 ]; then \
		echo "$(1): installing$$missing"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	else echo "$(1): missing$$missing; run: sudo apt-get install$$missing"; exit 1; fi

deps:
	@$(call deb_install,deps,$(DEB_PACKAGES))

# only for make fuzz (not needed by make or make check)
deps-fuzz:
	@$(call deb_install,deps-fuzz,$(FUZZ_PACKAGES))

# the editors' test: Debian's node, npm and vim, and vscode-tmgrammar-test from the npm registry,
# installed into the build directory (not into the tree, not globally)
deps-editors:
	@$(call deb_install,deps-editors,$(EDITOR_PACKAGES))
	@if [ -x $(BUILD)/editors-deps/node_modules/.bin/vscode-tmgrammar-test ]; then echo "deps-editors: $(TMGRAMMAR_TEST) present"; \
	else mkdir -p $(BUILD)/editors-deps && npm install --prefix $(BUILD)/editors-deps --no-audit --no-fund $(TMGRAMMAR_TEST); fi

# only for make bench-peers (not needed by make, make check or make bench)
deps-peers:
	@$(call deb_install,deps-peers,$(PEER_PACKAGES))

deps-cvode:
	@$(call deb_install,deps-cvode,$(CVODE_PACKAGES))

deps-box2d:
	@$(call deb_install,deps-box2d,$(BOX2D_PACKAGES))

# only for csfvm-mpi (make MPI=1) and its test
deps-mpi:
	@$(call deb_install,deps-mpi,$(MPI_PACKAGES))

# csfview's run-time packages alone (they are in make deps too)
deps-view:
	@$(call deb_install,deps-view,$(VIEW_PACKAGES) gnuplot-nox)

# only for the headless-browser test of csfview (big; make check skips that test without it)
deps-chromium:
	@$(call deb_install,deps-chromium,$(CHROMIUM_PACKAGES))

demo: deps
	$(MAKE) all
	$(BUILD)/csfc examples/projectile.csf -o $(BUILD)/projectile.csfb
	$(BUILD)/csfvm $(BUILD)/projectile.csfb | head -n 12
	$(BUILD)/csfvm $(BUILD)/projectile.csfb | $(BUILD)/csfview --scene examples/projectile.csf -o $(BUILD)/projectile.html
	@echo "the run, plotted and animated: $(abspath $(BUILD)/projectile.html)"

# where Debian's python3 finds the package: /usr/lib/python3/dist-packages for PREFIX=/usr, else
# PREFIX/lib/python3.X/dist-packages (site's directory for /usr/local)
PY_VERSION = $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null || echo 3)
PYTHON_DIR = $(if $(filter /usr,$(PREFIX)),$(PREFIX)/lib/python3/dist-packages,$(PREFIX)/lib/python$(PY_VERSION)/dist-packages)

install: all $(if $(SAN),,install-python)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/csf \
		$(DESTDIR)$(PREFIX)/share/csf/stdlib/mechanics $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/man/man5
	install -m 755 $(BUILD)/csfc $(BUILD)/csfvm $(DESTDIR)$(PREFIX)/bin/
	install -d $(DESTDIR)$(PREFIX)/share/csf/viewer
	sed 's|@VIEWDIR@|$(PREFIX)/share/csf/viewer|' viewer/csfview.sh >$(DESTDIR)$(PREFIX)/bin/csfview
	chmod 755 $(DESTDIR)$(PREFIX)/bin/csfview
	install -m 644 viewer/view.html viewer/view.js $(DESTDIR)$(PREFIX)/share/csf/viewer/
	install -m 644 $(BUILD)/libcsfrt.a $(DESTDIR)$(PREFIX)/lib/
	install -m 644 runtime/csf.h runtime/csf_ops.h runtime/opcodes.def $(DESTDIR)$(PREFIX)/include/csf/
	install -m 644 stdlib/mechanics/*.csf $(DESTDIR)$(PREFIX)/share/csf/stdlib/mechanics/
	install -m 644 man/csfc.1 man/csfvm.1 man/csfview.1 $(DESTDIR)$(PREFIX)/share/man/man1/
	install -m 644 man/csf.5 $(DESTDIR)$(PREFIX)/share/man/man5/
	install -d $(DESTDIR)$(PREFIX)/share/doc/csf/examples
	install -m 644 examples/*.csf examples/*.ipynb $(DESTDIR)$(PREFIX)/share/doc/csf/examples/
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$${prefix}/lib' 'includedir=$${prefix}/include' '' \
		'Name: csfrt' 'Description: CSF runtime library (integrator driver, loader, output) for generated models' \
		'Version: 0.1.0' 'Requires.private: gsl' 'Cflags: -I$${includedir}/csf -ffp-contract=off' \
		'Libs: -L$${libdir} -lcsfrt $(LDLIBS_H5) -lgsl -lgslcblas -lm' > $(DESTDIR)$(PREFIX)/lib/pkgconfig/csfrt.pc

# libcsf.so, its header, the Python package (its _paths.py naming the installed library and programs)
# and csf-python(7); not with SAN=1 (no libcsf.so there)
install-python: python
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/csf $(DESTDIR)$(PREFIX)/share/man/man7 \
		$(DESTDIR)$(PYTHON_DIR)/csf
	install -m 755 $(BUILD)/$(SO_NAME) $(DESTDIR)$(PREFIX)/lib/
	ln -sf $(SO_NAME) $(DESTDIR)$(PREFIX)/lib/libcsf.so
	install -m 644 runtime/api/csf_api.h $(DESTDIR)$(PREFIX)/include/csf/
	install -m 644 man/csf-python.7 man/csf-cookbook.7 $(DESTDIR)$(PREFIX)/share/man/man7/
	install -m 644 $(PY_SRC) $(DESTDIR)$(PYTHON_DIR)/csf/
	$(call py_paths,$(PREFIX)/lib,$(PREFIX)/bin) >$(DESTDIR)$(PYTHON_DIR)/csf/_paths.py

# removes exactly what install put there (and the directories it made, when empty)
uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/csfc $(DESTDIR)$(PREFIX)/bin/csfvm $(DESTDIR)$(PREFIX)/bin/csfview \
		$(DESTDIR)$(PREFIX)/share/csf/viewer/view.html $(DESTDIR)$(PREFIX)/share/csf/viewer/view.js \
		$(DESTDIR)$(PREFIX)/share/man/man1/csfview.1 $(DESTDIR)$(PREFIX)/lib/libcsfrt.a \
		$(DESTDIR)$(PREFIX)/lib/pkgconfig/csfrt.pc \
		$(DESTDIR)$(PREFIX)/include/csf/csf.h $(DESTDIR)$(PREFIX)/include/csf/csf_ops.h \
		$(DESTDIR)$(PREFIX)/include/csf/opcodes.def \
		$(DESTDIR)$(PREFIX)/share/man/man1/csfc.1 $(DESTDIR)$(PREFIX)/share/man/man1/csfvm.1 \
		$(DESTDIR)$(PREFIX)/share/man/man5/csf.5 $(DESTDIR)$(PREFIX)/share/man/man7/csf-python.7 \
		$(DESTDIR)$(PREFIX)/share/man/man7/csf-cookbook.7 \
		$(DESTDIR)$(PREFIX)/lib/$(SO_NAME) $(DESTDIR)$(PREFIX)/lib/libcsf.so $(DESTDIR)$(PREFIX)/include/csf/csf_api.h \
		$(DESTDIR)$(PYTHON_DIR)/csf/_paths.py $(addprefix $(DESTDIR)$(PYTHON_DIR)/csf/,$(notdir $(PY_SRC)))
	rm -rf $(DESTDIR)$(PYTHON_DIR)/csf/__pycache__
	-rmdir $(DESTDIR)$(PYTHON_DIR)/csf $(DESTDIR)$(PREFIX)/share/man/man7 2>/dev/null
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/share/csf/stdlib/mechanics/,$(notdir $(wildcard stdlib/mechanics/*.csf)))
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/share/doc/csf/examples/,$(notdir $(wildcard examples/*.csf examples/*.ipynb)))
	-rmdir $(DESTDIR)$(PREFIX)/include/csf $(DESTDIR)$(PREFIX)/share/csf/stdlib/mechanics $(DESTDIR)$(PREFIX)/share/csf/viewer \
		$(DESTDIR)$(PREFIX)/share/csf/stdlib $(DESTDIR)$(PREFIX)/share/csf \
		$(DESTDIR)$(PREFIX)/share/doc/csf/examples $(DESTDIR)$(PREFIX)/share/doc/csf 2>/dev/null

bench: all $(if $(HAVE_MPICC),$(BUILD)/csfvm-mpi)
	$(MAKE) -C bench BUILD=$(abspath $(BUILD))

bench-peers: all deps-peers
	$(MAKE) -C bench peers BUILD=$(abspath $(BUILD))

clean:
	rm -rf build build-san build-fuzz

.PHONY: python install-python all deps deps-editors deps-mpi deps-peers deps-cvode deps-box2d deps-view deps-chromium deps-fuzz demo test test-progs check check-piles fuzz fuzz-targets install uninstall bench bench-peers clean
