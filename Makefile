# The literate ray tracer: one non-recursive Makefile. It runs one job a
# core unless given -jN.
#
#   make              install missing packages (as root), tangle, build every
#                     bin/chNN, render the figures, build build/book.html
#   make test         every test: the tangler suite, each chapter's suites
#                     against every later chapter, src/ and figures up to date,
#                     the book's links, images and math, the commands it
#                     quotes, its layout and its scenes rendered in the page
#                     in Chromium (if installed) and, last,
#                     that no code line is wider than 80 columns
#   make chNN         build bin/chNN           make test-chNN  its suites
#   make run-chNN     render its own scene     make diff-chNN  what it adds
#   make src          rewrite the committed plain tangle src/chNN
#   make figures      render figures/chNN-*.png, the failure figures too
#   make failures     render figures/chNN-failure-*.png: what a naive method
#                     draws (left) next to what the program draws (right)
#   make charts       run bench/ (built with link-time optimization, under
#                     build/rel-lto) and redraw figures/chNN-*.svg; and
#                     chart-ch13_page: the page's programs against bin/chNN
#   make diagrams     redraw the explanatory figures/chNN-diagram-*.svg
#   make book         build/book.html          make clean
#   make wasm         build/wasm/chNN.wasm: each chapter's program for the
#                     book's page, which renders its scenes (part of make
#                     where clang can target wasm32-wasi: make installs it)
#   make check-page   the scenes rendered in the page in headless Chromium
#                     against bin/chNN (in make test where it is installed)
#   make book-check   the book in headless Chromium at 1280x900 (installs it
#                     as root): nothing wider than the text column, and a
#                     screenshot build/book-screenshot.png
#   make workbook     workbook/NN-name.md, the exercises to write (SOLVED=1:
#                     the book's code); make grade, grade-chNN, hint EX=2.1,
#                     watch; make chart-ch02 WORKBOOK=1 charts your forms
#                     (chapters 1 to 7)
#   make handout      build/handout/ and its .tar.gz: no solutions in it;
#                     its book.html renders the scenes with the page's
#                     programs (make check-handout-page, in make test)
#   make pdf, epub    the book's and the handout's editions
#   make SAN=1 test   what runs the programs (suites, figures, commands)
#                     with AddressSanitizer and UBSan
#   make WERROR=1     warnings are errors (CI)
#   make SCALAR=1, NATIVE=1   chapters 10 and 11's packets and node tests in
#                     scalar code, or with every instruction of this machine
#   make ALONE=1 test-chNN   chapter NN's program and suites built without
#                     the chapters before it (CI's sanitized pass)

.DELETE_ON_ERROR:
.SECONDARY:
.SUFFIXES:
.DEFAULT_GOAL := all

CC      ?= cc
# -ffp-contract=off: a compiler may otherwise fuse a*b + c into one
# multiply-add that rounds once, where chapter 4's error bounds count two
# roundings (Clang fuses by default wherever the machine has FMA).
CSTD    := -std=c11 -D_POSIX_C_SOURCE=200809L -ffp-contract=off
WARN    := -Wall -Wextra $(if $(WERROR),-Werror)
SANFLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
# make LTO=1 (make charts sets it): link-time optimization inlines across
# files: a ray's setup (mesh.c), its box test (box.c) and its triangle tests
# (triangle_methods.c) become one piece of code, which is what the charts
# measure. It costs a whole compile of the program at every link, so the
# everyday build goes without it. Inlined across files, GCC's
# maybe-uninitialized analysis warns of values that are always set before
# use; that warning keeps its per-file check at compile time.
LTO_FLAGS := $(if $(SAN),,$(if $(LTO),-flto=auto))
LTO_LINK := $(if $(LTO_FLAGS),-Wno-maybe-uninitialized)
OPT     := $(if $(SAN),$(SANFLAGS),-O2 -g $(LTO_FLAGS))
CFLAGS  ?=
LDFLAGS ?=
# make SCALAR=1: chapter 10's packets and chapter 11's node tests without
# vector instructions;
# make NATIVE=1: the instructions of the machine that builds (not needed
# for correctness). GCC 12.2 with AVX-512 stores a by-value struct built
# from a compound literal wrongly (a ray passed to mesh_ray_of, in chapter
# 8's tests); tools/book/probe_native.sh runs a three-line reproducer with this
# compiler and flags and adds -fno-tree-slp-vectorize only where the bug is.
# Each builds apart.
NATIVE_FIX := $(if $(NATIVE),$(shell sh tools/book/probe_native.sh "$(CC)" $(CSTD) $(OPT) -march=native))
ARCH    := $(if $(SCALAR),-DRT_SCALAR) $(if $(NATIVE),-march=native $(NATIVE_FIX))
# The suites (not the book's program) may use wait4, BSD's and Linux's, to
# read what a child process did. Check prints the doubles of a failed
# comparison with CK_FLOATING_DIG digits, 6 unless told: 17 tell any two
# doubles apart ("1 == 1" would be a length of 1.0000001 failing).
TEST_DEFS := -D_DEFAULT_SOURCE -D_DARWIN_C_SOURCE -DCK_FLOATING_DIG=17
# The suites' own code is compiled at -O0 (after the program's -O2, the
# last wins): it checks, the program computes, and -O0 compiles the large
# suite files in under half the time of -O1 (a third, with the sanitizers).
# The packet suite's loops are its work (half a million rays through the
# filter), and keep -O1.
TEST_OPT := -O0
$(B)/obj/%/tests/ch10_packets.o: TEST_OPT := -O1
# The sanitized pass runs each runner's tests in the runner's own process
# (tests/runner.c), but for those that need a process of their own: a
# sanitized child takes tens of milliseconds to start and to be checked for
# leaks as it exits, a minute of the pass over some three thousand tests.
# The first pass, forked and with time limits, has stopped any test that hangs.
RUNNER_ENV := $(if $(SAN),RUNNER_FORKLESS=1)
# In a handout (below) the static helpers and variables that only an
# exercise's code uses go unused until the student writes it, and so do the
# parameters of a function whose exercise is a fragment of its body (its
# stub, a return of zero, cannot call the book's compiled code).
ALL_CFLAGS = $(CSTD) $(WARN) $(HANDOUT_WARN) $(OPT) $(ARCH) -pthread $(CFLAGS) -MMD -MP
HANDOUT_WARN = $(if $(HANDOUT),-Wno-unused-function -Wno-unused-variable -Wno-unused-parameter $(if $(BOOK_CODE),,$(STUB_WARN)))
# (and where the stubs stand in, their parameters and variables too)
STUB_WARN = -Wno-unused-parameter -Wno-unused-variable -Wno-unused-but-set-variable -Wno-missing-braces

# Parallel by default, one job a core; make -jN still chooses, and a make
# run by a recipe shares its parent's jobs.
ifeq ($(MAKELEVEL),0)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || sysctl -n hw.ncpu 2>/dev/null || echo 2)
endif

# Asked once, when a recipe first needs them: after `deps` has had its
# chance to install them, and not again for each of hundreds of recipes.
once = $(eval $(1) := $$(shell $(2)))$($(1))
PNG_CFLAGS   = $(call once,PNG_CFLAGS,pkg-config --cflags libpng)
PNG_LIBS     = $(call once,PNG_LIBS,pkg-config --libs libpng)
CHECK_CFLAGS = $(call once,CHECK_CFLAGS,pkg-config --cflags check)
CHECK_LIBS   = $(call once,CHECK_LIBS,pkg-config --libs check)

# reuse_from NN OBJ: the start of a compile command of chapter NN that copies
# the previous chapter's OBJ instead when all it was compiled from is the
# same text (tools/book/reuse_object.c); nothing for the first chapter.
reuse_from = $(if $(call previous,$(1)),$(REUSE) $(B)/obj/ch$(call previous,$(1))/$(2) build/tangle/ch$(call previous,$(1)) build/tangle/ch$(1) -- )

# The target's folder, made when missing: no shell at all when it exists
# (hundreds of recipes, and a shell is not free).
dir_of_target = $(if $(wildcard $(@D)/.),,$(shell mkdir -p $(@D)))

# Sanitized builds live apart so that they never mix with normal objects,
# and so do another compiler's (make CC=clang): objects are remade when
# their sources change, not when the compiler does.
CC_TAG  := $(if $(filter cc gcc,$(notdir $(firstword $(CC)))),,-$(notdir $(firstword $(CC))))
B       := build/$(if $(SAN),san,rel)$(CC_TAG)$(if $(SCALAR),-scalar)$(if $(NATIVE),-native)$(if $(LTO_FLAGS),-lto)
BIN     := $(if $(SAN)$(SCALAR)$(NATIVE)$(LTO_FLAGS)$(CC_TAG),$(B)/bin,bin)
TANGLE  := $(B)/tools/book/tangle
REUSE   := $(B)/tools/book/reuse_object

CHAPTERS := $(sort $(wildcard chapters/[0-9][0-9]-*.md))
NUMS     := $(foreach c,$(CHAPTERS),$(firstword $(subst -, ,$(notdir $(c)))))

# link_meshes DIR DEPTH: scenes name meshes relative to themselves, so every
# tangled scenes/ folder gets a link to the repository's meshes/ folder.
link_meshes = if [ -d $(1)/scenes ]; then ln -sfn $(2)meshes $(1)/scenes/meshes; fi

# nums_upto NN: the two-digit numbers 01..NN, whether or not each has a chapter
DIGITS     := 0 1 2 3 4 5 6 7 8 9
TWO_DIGITS := $(filter-out 00,$(foreach a,$(DIGITS),$(addprefix $(a),$(DIGITS))))
nums_upto = $(wordlist 1,$(patsubst 0%,%,$(1)),$(TWO_DIGITS))
# chapters_upto NN: the Markdown of the chapters numbered 01..NN (a chapter
# may be written before the one before it: the numbers may have gaps)
chapters_upto = $(foreach c,$(CHAPTERS),$(if $(filter $(firstword $(subst -, ,$(notdir $(c)))),$(call nums_upto,$(1))),$(c)))
# The files the chapters declare with file="..." on a fence's line, each
# as NN:FILE (NN its chapter), read once (tools/book/file_decls.awk): every
# make, the grader's too, reads them.
FILE_DECLS := $(shell awk -f tools/book/file_decls.awk $(CHAPTERS))
# c_files NN: the .c files that chapters 01..NN declare with file="..."
c_files = $(sort $(foreach n,$(call nums_upto,$(1)),$(patsubst $(n):%,%,$(filter $(n):%.c,$(FILE_DECLS)))))
# scene_files NN: scenes declared by chapter NN itself, one figure each (found
# by number: chapters may be missing in between)
scene_files = $(sort $(patsubst $(1):%,%,$(filter $(1):scenes/ch$(1)-%.scene,$(FILE_DECLS))))
# suites_upto NN: the Check suites of chapters 01..NN
suites_upto = $(foreach n,$(filter $(call nums_upto,$(1)),$(NUMS)),$(wildcard tests/ch$(n)_*.c))
# previous NN: the chapter before NN, empty for the first
previous = $(lastword $(filter-out $(1),$(filter $(call nums_upto,$(1)),$(NUMS))))

# A handout (make handout) holds no exercise's code: its chapters hold the
# stubs, and the book's code of the exercises comes compiled, book/chNN.o,
# linked into every program of chapter NN, which calls it through
# book/forward/ and lets it call the student's code through book/export/
# (tools/workbook/book_code.sh, tools/workbook/book_code.awk): an exercise not started
# behaves as the book's code does. Each file is compiled with its name,
# -DRT_TU=NAME, which the names of those calls hold. On another machine
# than the one book/MACHINE names, the objects cannot serve: the stubs
# stand in for the exercises not started (BOOK_CODE is empty).
HANDOUT   := $(if $(wildcard book/MACHINE),yes)
BOOK_CODE := $(if $(HANDOUT),$(shell sh tools/workbook/book_code.sh machine book/MACHINE '$(CC)' && echo yes))
book_forms_upto = $(if $(BOOK_CODE),$(foreach k,forward export,$(foreach c,$(call chapters_upto,$(1)),book/$(k)/$(notdir $(c)))))
book_obj = $(if $(BOOK_CODE),book/ch$(1).o)
RT_TU = $(if $(HANDOUT),-DRT_TU=$(subst /,_,$*))
# where make book-code builds it for the handout (below)
BC := build/bookcode

.PHONY: all test deps src figures charts book clean check-src check-figures check-map check-stray check-allocations check-test-width \
        check-book check-lines check-quotes test-tangle tools benches \
        book-check check-book-browser check-page check-code-width check-commands

ifeq ($(HANDOUT),)
# (pandoc's weave first, which needs no program: it runs beside the
# compiles; the text woven before the page's programs are compiled)
all: deps build/book-refs.html $(foreach n,$(NUMS),$(BIN)/ch$(n)) figures build/book-text.html wasm book
else
# A handout's book comes woven (book.html), its figures made, and with the
# page's programs (the book's code compiled for WebAssembly where the
# handout was made) that render its scenes in its playgrounds: make builds
# the programs, which draw as the book's do, and the workbook.
all: deps $(foreach n,$(NUMS),$(BIN)/ch$(n)) workbook
	$(if $(BOOK_CODE),,@echo "make: book/ holds the book's code compiled for $$(head -n 1 book/MACHINE), \
	  not for this machine: the exercises you have not started are stubs here, and the \
	  tests that use them wait for you to write them (README.md)")
endif

deps:
	@sh tools/book/deps.sh

# ---------------------------------------------------------------- tools
$(B)/tools/%: tools/%.c | deps
	@$(dir_of_target)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LDFLAGS)

$(B)/tools/checks/pngdiff: tools/checks/pngdiff.c | deps
	@$(dir_of_target)
	$(CC) $(ALL_CFLAGS) $(PNG_CFLAGS) -o $@ $< $(LDFLAGS) $(PNG_LIBS)

tools: $(TANGLE) $(B)/tools/checks/check_book $(B)/tools/checks/pngdiff

-include $(wildcard $(B)/tools/book/*.d $(B)/tools/checks/*.d)

# ---------------------------------------------------------------- chapters
# One template, instantiated for every chapter NN.
define chapter_rules
T$(1)   := build/tangle/ch$(1)
O$(1)   := $(B)/obj/ch$(1)
SRC$(1) := $$(call c_files,$(1))
OBJ$(1) := $$(patsubst %.c,$$(O$(1))/%.o,$$(SRC$(1)))
LIB$(1) := $$(filter-out $$(O$(1))/main.o,$$(OBJ$(1)))
SUITES$(1) := $$(call suites_upto,$(1))
FIGS$(1) := figures/ch$(1)-default.png $$(patsubst scenes/%.scene,figures/%.png,$$(call scene_files,$(1)))

# The --line tangle is what gets compiled: errors point at the chapter.
$$(T$(1))/.stamp: $$(call chapters_upto,$(1)) $$(call book_forms_upto,$(1)) tools/book/tangle.c | $(TANGLE)
	@$$(dir_of_target)
	$(TANGLE) --line --strict -o $$(@D) $$(call chapters_upto,$(1)) $$(call book_forms_upto,$(1))
	@$$(call link_meshes,$$(@D),../../../../)
	@touch $$@

$$(T$(1))/%.c $$(T$(1))/%.h $$(T$(1))/%.scene: $$(T$(1))/.stamp ;

$$(O$(1))/%.o: $$(T$(1))/%.c | deps $(REUSE)
	@$$(dir_of_target)
	$(call reuse_from,$(1),$$*.o)$$(CC) $$(ALL_CFLAGS) $$(RT_TU) $$(PNG_CFLAGS) -I$$(T$(1)) -c -o $$@ $$<

$(BIN)/ch$(1): $$(OBJ$(1)) $$(call book_obj,$(1))
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(LTO_LINK) -o $$@ $$^ $$(LDFLAGS) $$(PNG_LIBS) -lm

ch$(1): deps $(BIN)/ch$(1)

# A file compiled in the chapter before is compiled first there, so that
# its object can serve here when nothing it was compiled from changed.
# make ALONE=1 builds a chapter without the chapters before it (its every
# file compiled): quicker where one late chapter is all that is wanted, as
# in CI's sanitized pass.
ifneq ($(if $(ALONE),,$(call previous,$(1))),)
$$(patsubst %.c,$$(O$(1))/%.o,$$(filter $$(SRC$(call previous,$(1))),$$(SRC$(1)))): \
  $$(O$(1))/%.o: | $(B)/obj/ch$(call previous,$(1))/%.o
$$(patsubst tests/%.c,$$(O$(1))/tests/%.o,$$(filter $$(SUITES$(call previous,$(1))),$$(SUITES$(1)))): \
  $$(O$(1))/tests/%.o: | $(B)/obj/ch$(call previous,$(1))/tests/%.o
endif

# The suites of chapters 01..NN, compiled against chapter NN's program.
$$(O$(1))/tests/%.o: tests/%.c $$(T$(1))/.stamp | deps $(REUSE)
	@$$(dir_of_target)
	$(call reuse_from,$(1),tests/$$*.o)$$(CC) $$(ALL_CFLAGS) $$(TEST_OPT) $$(TEST_DEFS) $$(PNG_CFLAGS) $$(CHECK_CFLAGS) -I$$(T$(1)) -c -o $$@ $$<

$$(O$(1))/tests/runner.o: tests/runner.c $$(SUITES$(1)) | deps
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(CHECK_CFLAGS) \
	  '-DSUITE_LIST=$$(foreach s,$$(SUITES$(1)),X($$(basename $$(notdir $$(s)))))' -c -o $$@ $$<

$(B)/test/ch$(1): $$(O$(1))/tests/runner.o $$(patsubst tests/%.c,$$(O$(1))/tests/%.o,$$(SUITES$(1))) $$(LIB$(1)) $$(call book_obj,$(1))
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(LTO_LINK) -o $$@ $$^ $$(LDFLAGS) $$(CHECK_LIBS) $$(PNG_LIBS) -lm

# a suite may compare the program with the previous chapter's (ties, ch08)
test-ch$(1): deps $(B)/test/ch$(1) $(BIN)/ch$(1) $(if $(call previous,$(1)),$(BIN)/ch$(call previous,$(1)))
	@echo "== suites 01..$(1) against the program of chapter $(1)"
	CHAPTER_BIN=$(BIN)/ch$(1) CK_DEFAULT_TIMEOUT=60 RUN_LOG=$(B)/test/ch$(1).log \
	  $(RUNNER_ENV) sh tools/checks/run_shards.sh $(B)/test/ch$(1)

run-ch$(1): $(BIN)/ch$(1)
	@mkdir -p build
	$(BIN)/ch$(1) -o build/ch$(1).png
	@echo "wrote build/ch$(1).png"

diff-ch$(1):
	@mkdir -p build/empty
	-diff -ruN $$(if $$(call previous,$(1)),src/ch$$(call previous,$(1)),build/empty) src/ch$(1)

# The committed plain tangle, for reading and diffing.
src-ch$(1): $(TANGLE)
	rm -rf src/ch$(1)
	$(TANGLE) --strict -o src/ch$(1) $$(call chapters_upto,$(1))
	@$$(call link_meshes,src/ch$(1),../../../)

check-src-ch$(1): $(TANGLE)
	@rm -rf build/srccheck/ch$(1)
	@$(TANGLE) --strict -o build/srccheck/ch$(1) $$(call chapters_upto,$(1))
	@$$(call link_meshes,build/srccheck/ch$(1),../../../../)
	@diff -r src/ch$(1) build/srccheck/ch$(1) >/dev/null || \
	  { echo "src/ch$(1) is not what the chapters tangle to: run 'make src' and commit"; \
	    diff -ru src/ch$(1) build/srccheck/ch$(1) | head -40; exit 1; }
	@echo "src/ch$(1): up to date"

# Figures: the default scene, and one per scenes/chNN-*.scene of the
# chapter, rendered once into $(B)/fig; figures/ gets the committed copies
# from there, and check-figures compares the same renders with git's HEAD.
$(B)/fig/ch$(1)-default.png: $(BIN)/ch$(1)
	@$$(dir_of_target)
	$(BIN)/ch$(1) -o $$@

$(B)/fig/ch$(1)-%.png: $$(T$(1))/scenes/ch$(1)-%.scene $(BIN)/ch$(1)
	@$$(dir_of_target)
	$(BIN)/ch$(1) $$< -o $$@

check-figures-ch$(1): $$(patsubst figures/%,$(B)/fig/%,$$(FIGS$(1))) $(B)/tools/checks/pngdiff
	@sh tools/checks/check_figures.sh $(B)/tools/checks/pngdiff $(B)/fig $$(FIGS$(1))

# Benchmarks link the chapter's program (all but main) like the tests do.
$$(O$(1))/bench/%.o: bench/%.c $$(T$(1))/.stamp | deps
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(PNG_CFLAGS) -I$$(T$(1)) -c -o $$@ $$<

$(B)/bench/ch$(1)_%: $$(O$(1))/bench/ch$(1)_%.o $$(O$(1))/bench/timing.o $$(LIB$(1))
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(LTO_LINK) -o $$@ $$^ $$(LDFLAGS) $$(PNG_LIBS) $$(BENCH_LIBS) -lm

# Failure figures (failures/chNN_*.c) link it the same way.
$$(O$(1))/failures/%.o: failures/%.c $$(T$(1))/.stamp | deps
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(PNG_CFLAGS) -I$$(T$(1)) -c -o $$@ $$<

$(B)/failures/ch$(1)_%: $$(O$(1))/failures/ch$(1)_%.o $$(LIB$(1))
	@$$(dir_of_target)
	$$(CC) $$(ALL_CFLAGS) $$(LTO_LINK) -o $$@ $$^ $$(LDFLAGS) $$(PNG_LIBS) -lm

-include $$(wildcard $$(O$(1))/*.d $$(O$(1))/tests/*.d $$(O$(1))/bench/*.d \
                     $$(O$(1))/failures/*.d)
endef

$(foreach n,$(NUMS),$(eval $(call chapter_rules,$(n))))

.PHONY: $(foreach n,$(NUMS),ch$(n) test-ch$(n) run-ch$(n) diff-ch$(n) src-ch$(n) \
          check-src-ch$(n) check-figures-ch$(n))

ALL_FIGS := $(foreach n,$(NUMS),$(FIGS$(n)))
BENCHES  := $(patsubst bench/%.c,$(B)/bench/%,$(wildcard bench/ch[0-9][0-9]_*.c))

# ---------------------------------------------------------------- failures
# failures/chNN_NAME.c renders what a naive method draws next to what the
# program draws, into figures/chNN-failure-NAME.png (NAME with - for _), and
# exits non-zero when the naive half no longer shows the failure.
FAILURES := $(wildcard failures/ch[0-9][0-9]_*.c)
failure_name = $(basename $(notdir $(1)))
failure_chapter = $(firstword $(subst _, ,$(call failure_name,$(1))))
failure_png = figures/$(call failure_chapter,$(1))-failure-$(subst _,-,$(patsubst \
                $(call failure_chapter,$(1))_%,%,$(call failure_name,$(1)))).png
FAILURE_BINS := $(foreach f,$(FAILURES),$(B)/failures/$(call failure_name,$(f)))
FAILURE_FIGS := $(foreach f,$(FAILURES),$(call failure_png,$(f)))

define failure_rule
$(B)/fig/$(notdir $(call failure_png,$(1))): $(B)/failures/$(call failure_name,$(1))
	@$$(dir_of_target)
	$$< $$@
endef
$(foreach f,$(FAILURES),$(eval $(call failure_rule,$(f))))

.PHONY: failures check-failures
failures: deps $(FAILURE_FIGS)

# The committed failure figures must be what the programs draw now (and
# each program exits non-zero, failing its render, when the naive half no
# longer shows the failure).
check-failures: $(patsubst figures/%,$(B)/fig/%,$(FAILURE_FIGS)) $(B)/tools/checks/pngdiff
	@sh tools/checks/check_figures.sh --made-by failures $(B)/tools/checks/pngdiff $(B)/fig $(FAILURE_FIGS)
	@echo "check-failures: $(words $(FAILURE_FIGS)) failure figures up to date"

# figures/ holds the committed copies of the renders in $(B)/fig: a copy is
# rewritten only when its bytes change, and left untouched otherwise, so
# that a render of the same picture (make test draws every figure again)
# does not weave the book, its editions and the handout again.
figures/%.png: $(B)/fig/%.png
	@cmp -s $< $@ || cp $< $@
	@touch -r $< $@ # not older than the render: checked once, not at every make

# Chapter 11 compares chapter 08's kd-tree with Intel Embree 3 where it is installed
# (Debian: libembree-dev); without it that benchmark is not built, and
# `make charts` draws its chart from this program's rates alone.
# Asked once, by the first make: its sub-makes (the grader's) get the answer.
ifeq ($(origin HAVE_EMBREE),undefined)
HAVE_EMBREE := $(shell printf '\043include <embree3/rtcore.h>\n' | \
                 $(CC) -E -x c - >/dev/null 2>&1 && echo yes)
endif
export HAVE_EMBREE
ifneq ($(HAVE_EMBREE),yes)
BENCHES  := $(filter-out %_embree,$(BENCHES))
endif
$(B)/bench/ch11_embree: BENCH_LIBS := -lembree3
# Chapter 12's build chart, and chapter 11's count of instructions a ray,
# show Embree beside ours where they can.
ifeq ($(HAVE_EMBREE),yes)
$(B)/bench/ch12_build: BENCH_LIBS := -lembree3
$(B)/obj/ch12/bench/ch12_build.o: ALL_CFLAGS += -DHAVE_EMBREE
$(B)/bench/ch11_instructions: BENCH_LIBS := -lembree3
$(B)/obj/ch11/bench/ch11_instructions.o: ALL_CFLAGS += -DHAVE_EMBREE
endif

src: $(foreach n,$(NUMS),src-ch$(n))
figures: $(ALL_FIGS) $(FAILURE_FIGS)
benches: $(BENCHES)
check-src: $(foreach n,$(NUMS),check-src-ch$(n))
check-figures: $(foreach n,$(NUMS),check-figures-ch$(n))

# The explanatory diagrams: programs in tools/diagrams/ compute every one's
# geometry and write figures/chNN-diagram-NAME.svg (committed, like the
# charts): diagrams.c draws chapters 1-7's, ch08_kdtree.c chapter 8's.
DIAGRAM_PROGRAMS := $(B)/tools/diagrams/diagrams $(B)/tools/diagrams/ch08_kdtree
.PHONY: diagrams check-diagrams
$(B)/tools/diagrams/%: tools/diagrams/%.c | deps
	@$(dir_of_target)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LDFLAGS) -lm

diagrams: $(DIAGRAM_PROGRAMS)
	@for p in $(DIAGRAM_PROGRAMS); do $$p figures || exit 1; done

# The committed diagrams must be what the programs draw now.
check-diagrams: $(DIAGRAM_PROGRAMS)
	@rm -rf build/diagramcheck && mkdir -p build/diagramcheck
	@for p in $(DIAGRAM_PROGRAMS); do $$p build/diagramcheck >/dev/null || exit 1; done
	@for f in build/diagramcheck/*.svg; do \
	  cmp -s $$f figures/$$(basename $$f) || \
	    { echo "figures/$$(basename $$f) is not what tools/diagrams draws: run 'make diagrams'"; exit 1; }; \
	done
	@echo "check-diagrams: $$(ls build/diagramcheck | wc -l) diagrams up to date"

# ---------------------------------------------------------------- charts
# bench/chNN_x.c writes figures/chNN-x.csv; bench/chNN_x.gp draws figures/chNN-x*.svg
# from it (gnuplot gets csv= the CSV and stem= figures/chNN-x). Every bench
# links bench/timing.c, the harness that times (bench/timing.h).
# One chart: make chart-ch02_sphere. All of them, one after another so that
# no two benchmarks share the machine: make charts.
# The harness prints the flags the benchmarks were compiled with on the
# machine line of every CSV.
$(foreach n,$(NUMS),$(B)/obj/ch$(n)/bench/timing.o): \
  ALL_CFLAGS += '-DBENCH_FLAGS="$(strip $(OPT) $(CFLAGS))"'

# Chapter 11's profile and count of instructions run the program under
# Valgrind's callgrind (Debian: valgrind, with the valgrind/callgrind.h
# that the two benchmarks are built with), installed first where it can be;
# without it, their charts say that it was absent.
.PHONY: deps-valgrind
deps-valgrind:
	@sh tools/book/deps.sh valgrind || echo "deps: no valgrind: chapter 11's counts will say so"
chart-ch11_profile chart-ch11_instructions: | deps-valgrind

# Chapter 13's chart of the programs in the page: each chapter's own scene
# rendered in the book's page (headless Chromium) and by bin/chNN, the
# everyday build, and by the same programs built by clang, the page's
# compiler, on one thread (tools/checks/page_check.sh --speed). It needs
# Chromium and the programs for the page; make charts draws it where it can.
.PHONY: chart-ch13_page chart-ch13_page-plain
PAGE_SPEED_SIZE := 640x480
PAGE_SPEED_ROUNDS := 11
chart-ch13_page: | deps
	+@$(MAKE) --no-print-directory LTO= chart-ch13_page-plain
chart-ch13_page-plain: build/book.html $(foreach n,$(NUMS),$(BIN)/ch$(n)) | deps
	+$(MAKE) --no-print-directory CC=clang $(foreach n,$(NUMS),build/rel-clang/bin/ch$(n))
	PAGE_SPEED_CLANG_BIN=build/rel-clang/bin \
	sh tools/checks/page_check.sh --speed figures/ch13-page.csv.tmp $(PAGE_SPEED_ROUNDS) \
	  build/book.html $(BIN) $(PAGE_SPEED_SIZE) $(NUMS)
	mv figures/ch13-page.csv.tmp figures/ch13-page.csv
	gnuplot -e "csv='figures/ch13-page.csv'; stem='figures/ch13-page'" bench/ch13_page.gp
	@echo "wrote figures/ch13-page.svg"

ifeq ($(LTO_FLAGS)$(SAN),)
# The charts measure the program built with link-time optimization. Two
# charts named at once (make chart-a chart-b) take turns on a lock (flock,
# util-linux): side by side they would time each other and build the same
# objects at once.
chart-%: | deps
	+@mkdir -p build && flock build/.charts.lock \
	  $(MAKE) --no-print-directory LTO=1 $@
charts charts-check: | deps
	+@$(MAKE) --no-print-directory LTO=1 $@
else
chart-%: $(B)/bench/% | deps
	$< > figures/$(subst _,-,$*).csv.tmp
	mv figures/$(subst _,-,$*).csv.tmp figures/$(subst _,-,$*).csv
	gnuplot -e "csv='figures/$(subst _,-,$*).csv'; stem='figures/$(subst _,-,$*)'" bench/$*.gp
	@echo "wrote figures/$(subst _,-,$*)*.svg"

charts: deps $(BENCHES)
	@for b in $(notdir $(BENCHES)); do $(MAKE) --no-print-directory chart-$$b || exit 1; done
	$(if $(filter 11,$(NUMS)),$(if $(HAVE_EMBREE),,@$(MAKE) --no-print-directory chart-embree-absent))
	@if [ -n "$(HAVE_WASM)" ] && . tools/editions/find_chromium.sh && [ -n "$$(find_chromium)" ]; then \
	  $(MAKE) --no-print-directory chart-ch13_page; \
	else echo "charts: figures/ch13-page.svg not measured: no Chromium or no programs for the page"; fi

# Can the speed axes be trusted? Every bench run twice: the largest ratio
# between two runs of a method, and whether an ordering a quoted ratio
# relies on flipped (tools/checks/charts_check.sh). Writes only build/charts-check.
charts-check: deps $(BENCHES)
	@sh tools/checks/charts_check.sh $(BENCHES)
endif

# Without Embree, chapter 11's comparison chart shows this program's own
# rates (from chapter 08's kd-tree benchmark) and says that Embree was absent.
.PHONY: chart-embree-absent
chart-embree-absent: figures/ch08-kdtree.csv
	{ grep '^# machine' figures/ch08-kdtree.csv; \
	  echo 'method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns'; \
	  grep -E '^kdtree,[^,]*,[^,]*,[^,]*,mrays_per_s(,|$$)|^kdtree-build,' figures/ch08-kdtree.csv; \
	  echo 'embree,absent,0,0,absent'; } > figures/ch11-embree.csv
	gnuplot -e "csv='figures/ch11-embree.csv'; stem='figures/ch11-embree'" bench/ch11_embree.gp

.PHONY: charts-check

# The committed charts must be what bench/*.gp draws from the committed CSVs
# (a .gp that learns to draw "yours" must not move a line of the book's).
.PHONY: check-charts
check-charts: | deps
	@rm -rf build/chartcheck && mkdir -p build/chartcheck
	@for gp in bench/ch*.gp; do s=$$(basename $$gp .gp | tr _ -); \
	  [ -f figures/$$s.csv ] || continue; \
	  gnuplot -e "csv='figures/$$s.csv'; stem='build/chartcheck/$$s'" $$gp || exit 1; done
	@for f in build/chartcheck/*.svg; do \
	  cmp -s $$f figures/$$(basename $$f) || \
	    { echo "figures/$$(basename $$f) is not what its .gp draws from its CSV"; exit 1; }; \
	done
	@echo "check-charts: $$(ls build/chartcheck | wc -l) charts redraw byte for byte from their CSVs"

# ---------------------------------------------------------------- workbook
# The reader writes the chunks a chapter marks .exercise (tools/workbook/exercises.awk
# lists them) in workbook/NN-name.md, and the chapters' tests grade them.
#   make workbook            one file per chapter, stubs that fail their tests;
#                            a file that exists is never overwritten
#   make workbook SOLVED=1   the book's own code in each stub, marked done
#   make grade, grade-chNN   build the program with the started exercises in
#                            place of the book's chunks, under build/workbook,
#                            and grade each exercise (tools/workbook/grade.sh)
#   make hint EX=2.1         that exercise's hint
#   make watch               grade again whenever a workbook file changes
# WB_DIR and WB_BUILD name another workbook and build folder (the tests).
# Another compiler or its flags build apart (build/workbook-rel-clang for
# make CC=clang), as the book's own build does: the objects follow only
# the text, and one compiler's would be taken as up to date for another's.
WB_DIR   ?= workbook
WB_TAG   := $(if $(filter build/rel,$(B)),,-$(notdir $(B)))
WB_BUILD ?= build/workbook$(WB_TAG)
$(WB_BUILD)/obj/%/tests/ch10_packets.o: TEST_OPT := -O1
WB_FILES := $(patsubst chapters/%,$(WB_DIR)/%,$(CHAPTERS))
# The reader's code is graded, not linted: a stub leaves parameters unused.
# The code is compiled as the book's is (the warnings do not change an
# object), so that a file that holds only the book's code takes the book's
# object (wb_reuse_book), and only what the reader wrote is compiled.
WB_CFLAGS = $(CSTD) -Wall -Wextra -Wno-unused-parameter -Wno-unused-function \
            -Wno-unused-variable -Wno-unused-but-set-variable -Wno-missing-braces \
            $(OPT) $(ARCH) -pthread $(CFLAGS) -MMD -MP
LAST     := $(lastword $(NUMS))

.PHONY: workbook grade hint watch $(foreach n,$(NUMS),grade-ch$(n))
workbook: $(WB_FILES)

# Order-only: a workbook file is the reader's, never remade once it exists.
$(WB_DIR)/%.md: | chapters/%.md
	@$(dir_of_target)
	awk -f tools/workbook/types.awk $(CHAPTERS) > $@.types
	awk -v solved=$(if $(SOLVED),1,0) -v types=$@.types -f tools/workbook/stub.awk -f tools/workbook/book_code.awk -f tools/workbook/workbook.awk \
	  chapters/$*.md chapters/$*.md > $@.tmp && mv $@.tmp $@; s=$$?; rm -f $@.types; exit $$s

# make grade EX=2.1: exercise 2.1's chapter graded, and the exit status is
# that exercise's verdict alone (0: done): one command an exercise, for an
# autograder. Every grade writes $(WB_BUILD)/junit.xml.
EX_CHAPTER := $(if $(EX),$(shell printf '%02d' '$(firstword $(subst ., ,$(EX)))' 2>/dev/null))
grade: $(if $(EX),grade-ch$(EX_CHAPTER),grade-ch$(LAST))

$(foreach n,$(NUMS),grade-ch$(n)): grade-ch%: $(TANGLE)
	+@TANGLE=$(TANGLE) WB_DIR=$(WB_DIR) WB_BUILD=$(WB_BUILD) MAKE="$(MAKE)" CC="$(CC)" \
	  GRADE_EX=$(EX) GRADE_BOOK_CODE=$(if $(HANDOUT),$(if $(BOOK_CODE),yes,no)) \
	  BOOK_BUILD=$(B) BOOK_BIN=$(BIN) sh tools/workbook/grade.sh $* $(call chapters_upto,$*)

hint:
	@if [ -z "$(EX)" ]; then \
	  echo "usage: make hint EX=N.k (an exercise's number, e.g. EX=2.1)" >&2; exit 2; fi
	@awk -v hint=$(EX) -f tools/workbook/exercises.awk $(CHAPTERS)

watch: $(TANGLE)
	+@WB_DIR=$(WB_DIR) WB_BUILD=$(WB_BUILD) sh tools/workbook/watch.sh $(MAKE) --no-print-directory \
	  WB_DIR=$(WB_DIR) WB_BUILD=$(WB_BUILD)

# make chart-chNN WORKBOOK=1: chapter NN's charts with the reader's started
# exercises as "yours", timed in the same rounds as the book's methods, under
# $(WB_BUILD)/charts (never figures/; tools/workbook/chart_yours.sh). A bench takes
# part with YOURS_<bench> (exercise=macro the bench knows), YOURS_OBJS_<bench>
# (the workbook objects that hold them) and YOURS_SYMS_<bench> (the functions
# renamed yours_...).
YOURS_ch01_srgb      := 1.2=YOURS_SRGB
YOURS_OBJS_ch01_srgb := image.o
YOURS_SYMS_ch01_srgb := srgb_encode srgb_to_byte gamma_encode
YOURS_ch02_sphere      := 2.1=YOURS_GEOMETRIC 2.2=YOURS_QUADRATIC 2.3=YOURS_ROBUST
YOURS_OBJS_ch02_sphere := sphere_roots.o sphere_roots_float.o
YOURS_SYMS_ch02_sphere := $(foreach f,geometric quadratic robust,sphere_roots_$(f) sphere_roots_$(f)_float)
YOURS_ch03_specular      := 3.1=YOURS_HIGHLIGHTS
YOURS_OBJS_ch03_specular := shade.o
YOURS_SYMS_ch03_specular := phong_cosine blinn_cosine specular_phong specular_blinn
YOURS_ch04_triangle      := 4.1=YOURS_SHEET 4.2=YOURS_MOLLER_TRUMBORE 4.3=YOURS_WATERTIGHT 4.4=YOURS_WATERTIGHT
YOURS_OBJS_ch04_triangle := triangle_methods.o triangle_methods_float.o
YOURS_SYMS_ch04_triangle := $(foreach f,sheet moller_trumbore watertight,triangle_hit_$(f) triangle_hit_$(f)_float)
YOURS_ch05_transform      := 5.3=YOURS_PRODUCTS
YOURS_OBJS_ch05_transform := mat4.o
YOURS_SYMS_ch05_transform := mat4_mul
YOURS_ch06_offset      := 6.1=YOURS_OFFSET
YOURS_OBJS_ch06_offset := offset.o
YOURS_SYMS_ch06_offset := offset_origin ray_leaving
YOURS_ch07_refract      := 7.1=YOURS_STANDARD 7.2=YOURS_SHEET
YOURS_OBJS_ch07_refract := optics.o
YOURS_SYMS_ch07_refract := refract_standard refract_sheet
YOURS_ch07_fresnel      := 7.3=YOURS_FRESNEL
YOURS_OBJS_ch07_fresnel := optics.o
YOURS_SYMS_ch07_fresnel := fresnel_exact fresnel_schlick fresnel_schlick_tir
YOURS_BENCHES := $(patsubst YOURS_OBJS_%,%,$(filter YOURS_OBJS_%,$(.VARIABLES)))
YOURS_NUMS    := $(sort $(foreach b,$(YOURS_BENCHES),$(patsubst ch%,%,$(firstword $(subst _, ,$(b))))))

define yours_chart_rule
.PHONY: chart-ch$(1)
chart-ch$(1): $(TANGLE) $$(LIB$(1)) $$(O$(1))/bench/timing.o | deps
	$$(if $$(WORKBOOK),,$$(error make chart-ch$(1) WORKBOOK=1 charts your methods; the book's charts are chart-ch$(1)_NAME))
	@GRADE_TANGLE_ONLY=1 TANGLE=$(TANGLE) WB_DIR=$(WB_DIR) WB_BUILD=$(WB_BUILD) \
	  sh tools/workbook/grade.sh $(1) $$(call chapters_upto,$(1))
	@$(MAKE) --no-print-directory -s WB_DIR=$(WB_DIR) WB_BUILD=$(WB_BUILD) \
	  $$(foreach b,$$(filter ch$(1)_%,$(YOURS_BENCHES)),$$(addprefix $$(WO$(1))/,$$(YOURS_OBJS_$$(b))))
	@drew=; $$(foreach b,$$(filter ch$(1)_%,$(YOURS_BENCHES)),sh tools/workbook/chart_yours.sh $$(b) \
	  $(WB_BUILD)/ch$(1)/state.tsv $(WB_BUILD)/charts "$$(YOURS_$$(b))" \
	  "$$(addprefix $$(WO$(1))/,$$(YOURS_OBJS_$$(b)))" "$$(YOURS_SYMS_$$(b))" "$(CC)" \
	  "$(ALL_CFLAGS) $(LTO_LINK) $(PNG_CFLAGS) -Ibench -I$$(T$(1))" \
	  $$(O$(1))/bench/timing.o $$(LIB$(1)) $(PNG_LIBS); \
	  case $$$$? in (0) drew=1 ;; (3) ;; (*) exit 1 ;; esac;) \
	[ -n "$$$$drew" ] || { echo "chart: start one of the exercises \
	  $$(foreach b,$$(filter ch$(1)_%,$(YOURS_BENCHES)),$$(foreach s,$$(YOURS_$$(b)),$$(firstword $$(subst =, ,$$(s))))) \
	  in the workbook first" >&2; exit 1; }
endef
$(foreach n,$(YOURS_NUMS),$(eval $(call yours_chart_rule,$(n))))

# make handout: build/handout/ and build/handout.tar.gz, the book for
# students: every exercise's code replaced by its stub, in the chapters and
# the woven book, with the workbook, tests, tools, meshes and figures; a
# student can make grade there. check-handout (in make test) builds it
# without the book and finds no solution line in it, compared without
# blanks and comments (but does in src/).
# The folder is made again only when what it is made from has changed
# (its book.html stands for it), and then without the editions of the
# old one; the tarball holds the folder with the editions made so far.
.PHONY: handout check-handout
# (Of the PNG figures, the renders, which make keeps up to date: a PNG
# that a benchmark writes has no rule here, and would be taken for one.)
HANDOUT_FROM := Makefile README.md book.md chapters/README.md $(CHAPTERS) \
                $(wildcard tools/* tools/*/* tools/*/*/* tests/* tests/*/* tests/*/*/* meshes/* meshes/*/*) \
                $(filter-out %.png,$(wildcard figures/*)) $(ALL_FIGS) $(FAILURE_FIGS)
# The editions asked for in this make, which the tarball must hold too.
# One that does not exist yet is made in this make, so the tarball is made
# again (said outright: make would not wait for a missing prerequisite of
# a tarball that is otherwise up to date, every file being .SECONDARY).
HANDOUT_EDITIONS := $(if $(filter pdf,$(MAKECMDGOALS)),build/handout/book.pdf) \
                    $(if $(filter epub,$(MAKECMDGOALS)),build/handout/book.epub)
HANDOUT_NEW := $(filter-out $(wildcard $(HANDOUT_EDITIONS)),$(HANDOUT_EDITIONS))
.PHONY: handout-editions-new
handout: build/handout.tar.gz

build/handout/book.html: $(HANDOUT_FROM) $(BC)/.forms $(foreach n,$(NUMS),$(BC)/ch$(n).o) | deps
	+CC="$(CC)" WEAVE_PAGE=$(PAGE_HTML) sh tools/workbook/handout.sh build/handout
	sh tools/checks/check_handout.sh build/handout

build/handout.tar.gz: build/handout/book.html $(HANDOUT_EDITIONS) $(if $(HANDOUT_NEW),handout-editions-new)
	tar -czf $@ -C build handout
	@echo "wrote build/handout/ and build/handout.tar.gz:" \
	  $$(cd build/handout && ls book.html book.pdf book.epub 2> /dev/null)

# The book's code of the exercises, compiled, for the handout (tools/
# book_code.sh): build/bookcode/forward/ and export/ (how the handout's
# programs call it, and it them), and build/bookcode/chNN.o, built from
# the chapters with each exercise's code in the book form of tools/
# book_code.awk, without debugging information.
BC_CFLAGS = $(CSTD) -O2 $(ARCH) -pthread -w -MMD -MP
.PHONY: book-code
book-code: $(foreach n,$(NUMS),$(BC)/ch$(n).o)
$(BC)/.forms: $(CHAPTERS) tools/workbook/stub.awk tools/workbook/book_code.awk tools/workbook/workbook.awk \
              tools/workbook/book_code.sh tools/workbook/exercises.awk $(T$(LAST))/.stamp
	@mkdir -p $(BC)
	sh tools/workbook/book_code.sh forms $(BC) $(T$(LAST)) $(CHAPTERS)
	@touch $@

define bookcode_rules
$(BC)/tangle/ch$(1)/.stamp: $(BC)/.forms | $(TANGLE)
	@$$(dir_of_target)
	$(TANGLE) --strict -o $$(@D) $$(call chapters_upto,$(1)) \
	  $$(foreach c,$$(call chapters_upto,$(1)),$(BC)/book/$$(notdir $$(c)))
	@touch $$@
$(BC)/tangle/ch$(1)/%.c $(BC)/tangle/ch$(1)/%.h: $(BC)/tangle/ch$(1)/.stamp ;
$(BC)/obj/ch$(1)/%.o: $(BC)/tangle/ch$(1)/%.c | deps $(REUSE)
	@$$(dir_of_target)
	$$(if $$(call previous,$(1)),$(REUSE) $(BC)/obj/ch$$(call previous,$(1))/$$*.o $(BC)/tangle/ch$$(call previous,$(1)) $(BC)/tangle/ch$(1) -- )$$(CC) $$(BC_CFLAGS) -DRT_TU=$$* $$(PNG_CFLAGS) -I$(BC)/tangle/ch$(1) -c -o $$@ $$<
ifneq ($(call previous,$(1)),)
$$(patsubst %.c,$(BC)/obj/ch$(1)/%.o,$$(filter $$(SRC$(call previous,$(1))),$$(SRC$(1)))): \
  $(BC)/obj/ch$(1)/%.o: | $(BC)/obj/ch$(call previous,$(1))/%.o
endif
$(BC)/ch$(1).o: $$(patsubst %.c,$(BC)/obj/ch$(1)/%.o,$$(SRC$(1))) tools/workbook/book_code.sh
	sh tools/workbook/book_code.sh link $$@ $$(filter %.o,$$^)
-include $$(wildcard $(BC)/obj/ch$(1)/*.d)
endef
$(if $(HANDOUT),,$(foreach n,$(NUMS),$(eval $(call bookcode_rules,$(n)))))

# The handout's book renders its scenes, for a student who has the
# tarball alone (build/handoutpage.tar.gz, made by the same script as
# make handout's but without the compiled book's code, which the page
# does not use and which would cost a build; HANDOUT_TARBALL=build/
# handout.tar.gz checks make handout's): unpacked in an empty folder, its page holds build/
# book.html's programs, meshes and scripts byte for byte (check-page
# renders every scene of that page), and chapter 3's highlights and the
# bunny render in it from file:// as bin/chNN draws them, offline
# (tools/checks/handout_page_check.sh; in headless Chromium where it is
# installed).
HANDOUT_PAGE_SCENES := 03:scenes/ch03-highlights.scene 08:scenes/ch08-bunny.scene
HANDOUT_TARBALL ?= build/handoutpage.tar.gz
.PHONY: check-handout-page
check-handout-page: $(HANDOUT_TARBALL) build/book.html \
                    $(foreach s,$(HANDOUT_PAGE_SCENES),$(BIN)/ch$(firstword $(subst :, ,$(s))))
	@sh tools/checks/handout_page_check.sh $(HANDOUT_TARBALL) build/book.html $(BIN) \
	  $(PAGE_CHECK_SIZE) $(HANDOUT_PAGE_SCENES)
build/handoutpage.tar.gz: $(HANDOUT_FROM) $(BC)/.forms | deps
	+@WEAVE_PAGE=$(PAGE_HTML) sh tools/workbook/handout.sh build/handoutpage --no-objects > /dev/null
	@tar -czf $@ -C build handoutpage
	@rm -rf build/handoutpage

# An untouched handout's programs pass the book's suites: the tarball
# unpacked in an empty folder and make test-ch$(LAST) run there, the book's
# compiled code standing in for every exercise (tools/checks/
# check_handout_programs.sh; in CI, not in make test: about a minute).
.PHONY: check-handout-programs
check-handout-programs: build/handout.tar.gz
	@sh tools/checks/check_handout_programs.sh build/handout.tar.gz $(LAST)

check-handout: $(BC)/.forms
	+@sh tools/workbook/handout.sh build/handoutcheck --no-book > /dev/null
	@sh tools/checks/check_handout.sh build/handoutcheck
	@! sh tools/checks/check_handout.sh src > /dev/null || \
	  { echo "check-handout: the check finds no solution in src/ either"; exit 1; }

# make pdf, make epub: both editions, the book's (build/book.pdf, .epub) and
# the handout's (build/handout/book.pdf, .epub), each made again only when
# what it is made from has changed, and the handout's tarball with them.
# The PDF is headless Chromium's print with the stylesheet's print rules
# (tools/editions/pdf.sh, which installs Chromium as root), the EPUB pandoc's,
# MathML kept, its links and SVG figures made valid EPUB (tools/editions/epub.sh).
# make check-editions checks the book's: every chapter starts a page of the
# PDF (where Chromium and pdftotext are installed), the EPUB is a whole zip
# whose navigation lists every chapter, and epubcheck finds no error in it
# (where epubcheck is installed: make installs it). It is not in make test,
# whose processor time printing and checking them would grow by a tenth;
# CI runs it beside make test.
.PHONY: pdf epub check-pdf check-epub check-editions
check-editions: check-epub check-pdf
pdf: build/book.pdf build/handout/book.pdf build/handout.tar.gz
epub: build/book.epub build/handout/book.epub build/handout.tar.gz

EPUB_TOOLS := tools/editions/epub.sh tools/editions/epub_links.awk tools/editions/epub_svg.awk
build/handout/book.pdf: build/handout/book.html tools/editions/pdf.sh
	sh tools/editions/pdf.sh $< $@
build/handout/book.epub: build/handout/book.html $(EPUB_TOOLS)
	cd build/handout && EPUB_PLAYGROUNDS=$$(grep -q 'id="rt-program-' book.html && echo yes) \
	  sh tools/editions/epub.sh book.md book.epub chapters/[0-9][0-9]-*.md

build/book.pdf: build/book.html tools/editions/pdf.sh
	sh tools/editions/pdf.sh $< $@

# (CHARTS is set further down: the charts are named here by wildcard.)
build/book.epub: book.md $(CHAPTERS) tools/book/weave.lua tools/book/weave_names.lua $(EPUB_TOOLS) \
                 tools/book/book.css $(ALL_FIGS) $(FAILURE_FIGS) $(wildcard figures/ch[0-9][0-9]-*.svg) | deps
	EPUB_PLAYGROUNDS=$(HAVE_WASM) sh tools/editions/epub.sh book.md $@ $(CHAPTERS)

check-epub: build/book.epub
	@sh tools/checks/check_epub.sh $< $(CHAPTERS)

HAVE_PDF_TOOLS = $(shell (command -v chromium || command -v chromium-browser || \
                   command -v google-chrome) >/dev/null 2>&1 && \
                   command -v pdftotext >/dev/null 2>&1 && echo yes)
# The PDF is a prerequisite, not a sub-make: a make of its own would link
# the programs at the same time as this one.
check-pdf: $(if $(HAVE_PDF_TOOLS),build/book.pdf)
	@if [ "$(HAVE_PDF_TOOLS)" = yes ]; then \
	  sh tools/checks/check_pdf.sh build/book.pdf $(CHAPTERS); \
	else echo "check-pdf: skipped: no chromium or no pdftotext (make pdf installs Chromium)"; fi

# Each stub alone must fail its tests (minutes: not in make test).
.PHONY: check-stubs
check-stubs: $(TANGLE)
	+@MAKE="$(MAKE)" sh tools/checks/check_stubs.sh

# The workbook's own tests (tools/checks/check_workbook.sh), in build/wbcheck
# (another compiler's, as make grade's, in a folder of its own).
# Its grades run side by side, each a make of its own that takes the book's
# objects of the chapters it grades (and of the chapters before them): this
# make builds those first, so that no two makes write one object at once.
# The book's code, typed in, builds the book's programs byte for byte: the
# last chapter's suites, run first, give that grade its results.
WB_CHECK_CHAPTERS := $(NUMS)
.PHONY: check-workbook
check-workbook: $(TANGLE) $(foreach n,$(filter $(NUMS),$(WB_CHECK_CHAPTERS)),$(B)/test/ch$(n) $(BIN)/ch$(n)) \
                test-ch$(LAST)
	+@MAKE="$(MAKE)" TANGLE=$(TANGLE) CC="$(CC)" BOOK_BUILD=$(B) BOOK_BIN=$(BIN) \
	  WB_CHECK_DIR=build/wbcheck$(WB_TAG) sh tools/checks/check_workbook.sh

# The workbook's program and suites of chapter NN, built from the tangle
# that tools/workbook/grade.sh writes to $(WB_BUILD)/tangle/chNN. What the
# compiler says of a file is kept beside its object, OBJ.warnings: the
# grader shows the warnings at the reader's lines at every grade, whether
# or not the file was compiled again.
define workbook_rules
WT$(1) := $(WB_BUILD)/tangle/ch$(1)
WO$(1) := $(WB_BUILD)/obj/ch$(1)
WOBJ$(1) := $$(patsubst %.c,$$(WO$(1))/%.o,$$(SRC$(1)))
WLIB$(1) := $$(filter-out $$(WO$(1))/main.o,$$(WOBJ$(1)))

$$(WO$(1))/%.o: $$(WT$(1))/%.c $$(O$(1))/%.o | deps $(REUSE)
	@$$(dir_of_target)
	$$(call wb_reuse_book,$(1),$$*.o) $$(call wb_reuse_from,$(1),$$*.o)$$(CC) $$(WB_CFLAGS) $$(RT_TU) $$(PNG_CFLAGS) -I$$(WT$(1)) -c -o $$@ $$< \
	  2> $$@.warnings || { cat $$@.warnings >&2; exit 1; }
	@cat $$@.warnings >&2

$$(WO$(1))/tests/%.o: tests/%.c $$(O$(1))/tests/%.o | deps $(REUSE)
	@$$(dir_of_target)
	$$(call wb_reuse_book,$(1),tests/$$*.o) $$(call wb_reuse_from,$(1),tests/$$*.o)$$(CC) $$(WB_CFLAGS) $$(TEST_OPT) $$(TEST_DEFS) $$(PNG_CFLAGS) $$(CHECK_CFLAGS) -I$$(WT$(1)) -c -o $$@ $$<

$$(WO$(1))/tests/runner.o: tests/runner.c $$(SUITES$(1)) | deps
	@$$(dir_of_target)
	$$(CC) $$(WB_CFLAGS) $$(CHECK_CFLAGS) \
	  '-DSUITE_LIST=$$(foreach s,$$(SUITES$(1)),X($$(basename $$(notdir $$(s)))))' -c -o $$@ $$<

$(WB_BUILD)/test/ch$(1): $$(WO$(1))/tests/runner.o \
                      $$(patsubst tests/%.c,$$(WO$(1))/tests/%.o,$$(SUITES$(1))) $$(WLIB$(1)) \
                      $$(call book_obj,$(1))
	@$$(dir_of_target)
	$$(CC) $$(WB_CFLAGS) -o $$@ $$^ $$(LDFLAGS) $$(CHECK_LIBS) $$(PNG_LIBS) -lm

$(WB_BUILD)/bin/ch$(1): $$(WOBJ$(1)) $$(call book_obj,$(1))
	@$$(dir_of_target)
	$$(CC) $$(WB_CFLAGS) -o $$@ $$^ $$(LDFLAGS) $$(PNG_LIBS) -lm

# The suites again, the files that hold the reader's code (WB_TSAN_FILES,
# their names without .c: tools/workbook/grade.sh) built with ThreadSanitizer, the
# rest as they are: the tests that start threads run in it. Without
# optimization, so that every access the code makes is made (at -O2 a
# static variable that a function writes and reads may live in a
# register, and its race go unseen).
$(WB_BUILD)/tsan/obj/ch$(1)/%.o: $$(WT$(1))/%.c | deps
	@$$(dir_of_target)
	$$(CC) $$(WB_CFLAGS) -O0 -fsanitize=thread $$(RT_TU) $$(PNG_CFLAGS) -I$$(WT$(1)) -c -o $$@ $$<

$(WB_BUILD)/tsan/test/ch$(1): $$(WO$(1))/tests/runner.o \
                      $$(patsubst tests/%.c,$$(WO$(1))/tests/%.o,$$(SUITES$(1))) \
                      $$(foreach o,$$(WLIB$(1)),$$(if $$(filter $$(basename $$(notdir $$(o))),$$(WB_TSAN_FILES)),$(WB_BUILD)/tsan/obj/ch$(1)/$$(notdir $$(o)),$$(o))) \
                      $$(call book_obj,$(1))
	@$$(dir_of_target)
	$$(CC) $$(WB_CFLAGS) -fsanitize=thread -o $$@ $$^ $$(LDFLAGS) $$(CHECK_LIBS) $$(PNG_LIBS) -lm

-include $$(wildcard $$(WO$(1))/*.d $$(WO$(1))/tests/*.d $(WB_BUILD)/tsan/obj/ch$(1)/*.d)
endef
$(foreach n,$(NUMS),$(eval $(call workbook_rules,$(n))))

# wb_reuse_book NN OBJ: the book's own object of chapter NN (made first: a
# prerequisite, so that a book object made again, its lines moved, is
# copied again) serves when the workbook's tangle of the file and its
# headers is the book's code, #line directives aside.
wb_reuse_book = $(REUSE) --code $(B)/obj/ch$(1)/$(2) build/tangle/ch$(1) $(WB_BUILD)/tangle/ch$(1) --

# WB_REUSE=NN (tools/workbook/grade.sh sets it): chapter NN's program is built with
# the chapter before it, whose program some suites compare with; a file of
# NN that is the same text as there, with the same headers, is compiled
# there first and its object copied (tools/book/reuse_object).
wb_reuse_from = $(if $(filter $(1),$(WB_REUSE)),$(if $(call previous,$(1)),$(REUSE) $(WB_BUILD)/obj/ch$(call previous,$(1))/$(2) $(WB_BUILD)/tangle/ch$(call previous,$(1)) $(WB_BUILD)/tangle/ch$(1) -- ))
define workbook_reuse_rules
$$(patsubst %.c,$(WB_BUILD)/obj/ch$(1)/%.o,$$(filter $$(SRC$(2)),$$(SRC$(1)))): \
  $(WB_BUILD)/obj/ch$(1)/%.o: | $(WB_BUILD)/obj/ch$(2)/%.o
$$(patsubst tests/%.c,$(WB_BUILD)/obj/ch$(1)/tests/%.o,$$(filter $$(SUITES$(2)),$$(SUITES$(1)))): \
  $(WB_BUILD)/obj/ch$(1)/tests/%.o: | $(WB_BUILD)/obj/ch$(2)/tests/%.o
endef
ifneq ($(and $(WB_REUSE),$(call previous,$(WB_REUSE))),)
$(eval $(call workbook_reuse_rules,$(WB_REUSE),$(call previous,$(WB_REUSE))))
endif

# ---------------------------------------------------------------- fuzzing
# make fuzz FUZZ_SECONDS=60: each libFuzzer target for that long, built with
# clang, ASan and UBSan against the latest chapter's program. New inputs go to
# build/fuzz/corpus/NAME; the committed seeds in fuzz/corpus/NAME are read only.
# A finding leaves its input in build/fuzz/NAME-crash-* (or leak-, timeout-).
FUZZ_SECONDS ?= 60
FUZZ_CHAPTER := $(lastword $(NUMS))
FUZZ_TARGETS := tangle scene obj
FUZZ_FLAGS   := $(CSTD) -g -O1 -fno-omit-frame-pointer -fsanitize=address,undefined \
                -fno-sanitize-recover=all
FUZZ_LIB     := $(patsubst %.c,build/fuzz/obj/%.o,$(filter-out main.c,$(call c_files,$(FUZZ_CHAPTER))))

.PHONY: fuzz fuzz-deps fuzz-build
fuzz-deps:
	@sh tools/book/deps.sh clang libclang-rt-dev

build/fuzz/obj/%.o: build/tangle/ch$(FUZZ_CHAPTER)/%.c | fuzz-deps
	@$(dir_of_target)
	clang $(FUZZ_FLAGS) -fsanitize=fuzzer-no-link $(PNG_CFLAGS) -Ibuild/tangle/ch$(FUZZ_CHAPTER) -c -o $@ $<

build/fuzz/tangle_fuzz: fuzz/tangle_fuzz.c tools/book/tangle.c | fuzz-deps
	@$(dir_of_target)
	clang $(FUZZ_FLAGS) -fsanitize=fuzzer -Dmain=tangle_main -o $@ $^

build/fuzz/%_fuzz: fuzz/%_fuzz.c $(FUZZ_LIB) | fuzz-deps
	@$(dir_of_target)
	clang $(FUZZ_FLAGS) -fsanitize=fuzzer $(PNG_CFLAGS) -Ibuild/tangle/ch$(FUZZ_CHAPTER) \
	  -o $@ $^ $(PNG_LIBS) -lm

fuzz-build: $(foreach t,$(FUZZ_TARGETS),build/fuzz/$(t)_fuzz)

# The targets run side by side, all at once whatever the jobs (so that
# FUZZ_SECONDS is the whole run's time on the clock), by tools/checks/fuzz.sh;
# make fuzz-run-NAME runs one alone.
FUZZ_RUNS := $(addprefix fuzz-run-,$(FUZZ_TARGETS))
.PHONY: $(FUZZ_RUNS)
fuzz: fuzz-build
	@sh tools/checks/fuzz.sh $(FUZZ_SECONDS) $(FUZZ_TARGETS)
	@echo "make fuzz: $(FUZZ_TARGETS) ran $(FUZZ_SECONDS) s each and found nothing"

$(FUZZ_RUNS): fuzz-run-%: build/fuzz/%_fuzz
	@sh tools/checks/fuzz.sh $(FUZZ_SECONDS) $*

# ---------------------------------------------------------------- valgrind
# make valgrind: every test binary (its tests in its own process, so that
# valgrind sees them, but for those that need one of their own: runner.c)
# and every chapter binary on each of its scenes, small.
VALGRIND := valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=all -q

.PHONY: valgrind
valgrind: all $(B)/test/tangle $(foreach n,$(NUMS),$(B)/test/ch$(n))
	@mkdir -p build/valgrind
	RUNNER_FORKLESS=1 TANGLE=$(TANGLE) $(VALGRIND) $(B)/test/tangle
	$(VALGRIND) $(TANGLE) --line --strict -o build/valgrind/tangle $(CHAPTERS)
	@for n in $(NUMS); do \
	  echo "== valgrind: suites 01..$$n and bin/ch$$n"; \
	  RUNNER_FORKLESS=1 CHAPTER_BIN=$(BIN)/ch$$n $(VALGRIND) $(B)/test/ch$$n || exit 1; \
	  $(VALGRIND) $(BIN)/ch$$n --size 64x48 -o build/valgrind/ch$$n.png || exit 1; \
	  for scene in build/tangle/ch$$n/scenes/ch$$n-*.scene; do \
	    [ -f $$scene ] || continue; \
	    $(VALGRIND) $(BIN)/ch$$n $$scene --size 64x48 -o build/valgrind/ch$$n.png || exit 1; \
	  done; \
	done
	@echo "make valgrind: clean"

# ---------------------------------------------------------------- the page
# Each chapter's program compiled for WebAssembly, for the book's page to
# render its scenes (chapter 13): the same
# files as bin/chNN, with the headers of the last chapter's page/ folder
# in front of the system's. make installs the toolchain as root (Debian:
# clang lld wasi-libc libclang-rt-dev-wasm32, tools/book/deps.sh --page);
# without it the programs are skipped, and the book has no playground.
# make page-check (in make test where Chromium is installed) renders
# every chapter's scenes in the book's page in headless Chromium.
WASM_CC   := clang --target=wasm32-wasi
PAGE_DIR  := build/tangle/ch$(LAST)/page
# Asked once, by the first make: its sub-makes get the answer from it.
ifndef PAGE_PROBED
HAVE_WASM := $(if $(filter clean,$(MAKECMDGOALS))$(HANDOUT),,$(shell sh tools/book/deps.sh --page >&2; \
               printf 'int main(void) { return 0; }\n' | \
               $(WASM_CC) -x c - -o /dev/null >/dev/null 2>&1 && echo yes))
export HAVE_WASM
export PAGE_PROBED := 1
endif
# No debugging information: the page is one file, and it carries them all.
WASM_CFLAGS = $(CSTD) $(WARN) -O2 -I$(PAGE_DIR) -include $(PAGE_DIR)/page.h -MMD -MP
# A scene's trees recurse: a stack of 8 MiB, as a Linux thread has.
WASM_LDFLAGS := -Wl,--strip-all -Wl,-z,stack-size=8388608

define page_rules
PO$(1) := build/wasm/obj/ch$(1)
$$(PO$(1))/%.o: $$(T$(1))/%.c | $$(T$(LAST))/.stamp $(REUSE)
	@$$(dir_of_target)
	$$(if $$(call previous,$(1)),$(REUSE) build/wasm/obj/ch$$(call previous,$(1))/$$*.o build/tangle/ch$$(call previous,$(1)) $$(T$(1)) -- )$(WASM_CC) $$(WASM_CFLAGS) -I$$(T$(1)) -c -o $$@ $$<

build/wasm/ch$(1).wasm: $$(patsubst %.c,$$(PO$(1))/%.o,$$(SRC$(1)))
	@$$(dir_of_target)
	$(WASM_CC) -O2 $(WASM_LDFLAGS) -o $$@ $$^ -lm

ifneq ($(call previous,$(1)),)
$$(patsubst %.c,$$(PO$(1))/%.o,$$(filter $$(SRC$(call previous,$(1))),$$(SRC$(1)))): \
  $$(PO$(1))/%.o: | build/wasm/obj/ch$(call previous,$(1))/%.o
endif
-include $$(wildcard $$(PO$(1))/*.d)
endef
$(foreach n,$(NUMS),$(eval $(call page_rules,$(n))))

WASM_PROGRAMS := $(if $(HAVE_WASM),$(foreach n,$(NUMS),build/wasm/ch$(n).wasm))
PAGE_MESHES := $(wildcard meshes/*.obj)
# Each program and mesh as the page holds it, gzip'd (-n: the same bytes
# every time) and in base64, made apart so that a build remakes only the
# programs that changed, side by side.
build/page/%.wasm.b64: build/wasm/%.wasm
	@$(dir_of_target)
	gzip -9 -n -c $< | base64 -w 76 > $@
build/page/%.obj.b64: meshes/%.obj
	@$(dir_of_target)
	gzip -9 -n -c $< | base64 -w 76 > $@
build/page/playground.html: $(patsubst build/wasm/%,build/page/%.b64,$(WASM_PROGRAMS)) \
                            $(patsubst meshes/%,build/page/%.b64,$(PAGE_MESHES)) \
                            tools/editions/page.sh $(wildcard tools/editions/page/*)
	sh tools/editions/page.sh $@ $(patsubst build/wasm/%,build/page/%.b64,$(WASM_PROGRAMS)) \
	  -- $(patsubst meshes/%,build/page/%.b64,$(PAGE_MESHES))
.PHONY: wasm
wasm: $(WASM_PROGRAMS)
	$(if $(HAVE_WASM),,@echo "wasm: skipped: no clang for wasm32-wasi (Debian: apt-get install clang lld wasi-libc libclang-rt-dev-wasm32); the book has no playground")

# ---------------------------------------------------------------- book
CHARTS := $(wildcard figures/ch[0-9][0-9]-*.svg)

book: build/book.html
# With the programs for the page (above), the page renders the scenes.
PAGE_HTML := $(if $(HAVE_WASM),build/page/playground.html)
# The book is woven in steps: pandoc's (a core for seconds), which needs
# no figure and runs while the programs are compiled; the figures and the
# CSS put in, in a moment, once they are drawn; the page's HTML added at
# the end, once its programs are compiled for WebAssembly.
build/book-refs.html: book.md $(CHAPTERS) tools/book/weave.lua tools/book/weave_names.lua \
                      tools/book/weave.sh | deps
	@$(dir_of_target)
	sh tools/book/weave.sh --text book.md $@ $(CHAPTERS)
build/book-text.html: build/book-refs.html tools/book/weave.sh tools/book/book.css \
                      $(ALL_FIGS) $(FAILURE_FIGS) $(CHARTS)
	sh tools/book/weave.sh --embed $< $@
build/book.html: build/book-text.html $(PAGE_HTML)
	$(if $(PAGE_HTML),sh tools/book/weave.sh --page $(PAGE_HTML) $< $@,cp $< $@)
# The handout's book holds the same programs (make handout, above).
build/handout/book.html build/handoutpage.tar.gz: $(PAGE_HTML)

# The weaver stops at a chunk no program uses: a made-up chapter woven
# with and without one.
.PHONY: check-weave-errors
check-weave-errors: | deps
	@d=$$(mktemp -d) && \
	printf '# A\n\n```{.c file="a.c"}\nint main(void) { return 0; }\n<<used>>\n```\n\n```{.c chunk="used"}\nint y;\n```\n' > $$d/01-a.md && \
	sh tools/book/weave.sh book.md $$d/good.html $$d/01-a.md > $$d/log 2>&1 || \
	  { cat $$d/log; echo "check-weave-errors: a good chapter did not weave"; rm -rf $$d; exit 1; }; \
	printf '\n```{.c chunk="unused"}\nint x;\n```\n' >> $$d/01-a.md; \
	if sh tools/book/weave.sh book.md $$d/bad.html $$d/01-a.md > $$d/log 2>&1 || \
	   ! grep -q '<<unused>> is defined but never used' $$d/log; then \
	  cat $$d/log; echo "check-weave-errors: an unused chunk did not stop the weave"; rm -rf $$d; exit 1; fi; \
	printf '\n![A picture.](figures/no-such-figure.png)\n' > $$d/02-b.md; \
	if sh tools/book/weave.sh book.md $$d/bad.html $$d/02-b.md > $$d/log 2>&1 || \
	   ! grep -q 'missing resource: figures/no-such-figure.png' $$d/log || [ -e $$d/bad.html ]; then \
	  cat $$d/log; echo "check-weave-errors: a missing figure did not stop the weave"; rm -rf $$d; exit 1; fi; \
	rm -rf $$d; echo "check-weave-errors: an unused chunk and a missing figure stop the weave: ok"

check-book: build/book.html $(B)/tools/checks/check_book
	$(B)/tools/checks/check_book build/book.html

# Every line of every code box fits 80 columns (names the chunk if not).
check-code-width: build/book.html $(B)/tools/checks/check_book
	$(B)/tools/checks/check_book --code-width 80 build/book.html

# The page in headless Chromium at 1280x900: make book-check installs it
# when missing (as root); make test only runs it if it is there.
book-check: build/book.html
	sh tools/checks/book_check.sh build/book.html build/book-screenshot.png

# The same check without a screenshot, where Chromium is installed (make
# test has check-page make it, in the load of the page that its renders use).
check-book-browser: build/book.html
	@sh tools/checks/book_check.sh --no-install build/book.html -

# The scenes rendered in the page against the programs' own PNGs (at a
# small size, to be quick), a located mistake, a cancelled render, the
# network off, and first, in the same load of the page, check-book-browser's
# layout at 1280 x 900: headless Chromium, where it is installed
# (tools/checks/page_check.sh; without node, the layout alone).
PAGE_CHECK_SIZE := 160x120
check-page: build/book.html $(foreach n,$(NUMS),$(BIN)/ch$(n))
	@sh tools/checks/page_check.sh build/book.html $(BIN) $(PAGE_CHECK_SIZE) $(NUMS)

# Every bin/chNN command the book and README quote runs (the self-test
# first: the check must be able to fail).
check-commands: $(foreach n,$(NUMS),$(BIN)/ch$(n))
	@sh tools/checks/check_commands.sh --self-test
	@sh tools/checks/check_commands.sh --bin $(BIN) chapters/*.md book.md README.md

# ---------------------------------------------------------------- tests
$(B)/test/tangle: tests/runner.c tests/tangle_test.c | deps
	@$(dir_of_target)
	$(CC) $(ALL_CFLAGS) $(CHECK_CFLAGS) '-DSUITE_LIST=X(tangle)' -o $@ $^ $(LDFLAGS) $(CHECK_LIBS)

test-tangle: $(B)/test/tangle $(TANGLE)
	@echo "== the tangler's suite"
	TANGLE=$(TANGLE) CK_DEFAULT_TIMEOUT=60 $(RUNNER_ENV) sh tools/checks/run_shards.sh $(B)/test/tangle

# A syntax error typed into chapter 01 must be reported at its Markdown line.
check-lines: $(TANGLE) | deps
	@sh tools/checks/check_line_directives.sh $(TANGLE) chapters/01-camera.md 'double half_width = tan('

# The numbers the chapters quote must be the ones in the CSV files of make charts.
check-quotes:
	@sh tools/checks/check_quotes.sh bench/quotes.txt

# Every paragraph of prose closes the brackets it opens (pandoc would scan
# the rest of the book for each: tools/checks/check_brackets.awk).
.PHONY: check-brackets
check-brackets:
	@awk -f tools/checks/check_brackets.awk book.md $(CHAPTERS)
	@echo "check-brackets: every paragraph closes its brackets"

# tools/book/reuse_object copies an object only for the same code.
.PHONY: check-reuse
check-reuse: $(REUSE)
	@sh tools/checks/check_reuse.sh $(REUSE) $(CC)

# The README quotes the build's own speed as bench/build_speed.sh measured
# it (figures/build-speed.md): every line of that table, word for word.
.PHONY: check-build-speed
check-build-speed:
	@[ -f figures/build-speed.md ] || { echo "figures/build-speed.md: missing: run sh bench/build_speed.sh --ci"; exit 1; }
	@while IFS= read -r line; do [ -z "$$line" ] || grep -qxF -- "$$line" README.md || \
	  { echo "README.md: error: does not quote figures/build-speed.md's line: $$line"; exit 1; }; \
	done < figures/build-speed.md
	@echo "check-build-speed: README.md quotes figures/build-speed.md"

# chapters/README.md's map of layers and hooks is that of the last chapter,
# and every file of tools/ is in a folder whose README.md names it.
check-map: check-src
	@sh tools/checks/check_map.sh --self-test
	@sh tools/checks/check_map.sh chapters/README.md src/ch$(lastword $(NUMS)) $(CHAPTERS)
	@sh tools/checks/check_map.sh --tools tools

# Every allocation of the last chapter's program goes through memory.h.
check-allocations: check-src
	@if grep -nE '\<(malloc|calloc|realloc|strdup|aligned_alloc)\(' \
	    $$(ls src/ch$(lastword $(NUMS))/*.[ch] | grep -v '/memory\.c$$'); then \
	  echo "allocations outside memory.c: use memory.h"; exit 1; fi
	@echo "every allocation goes through memory.h: ok"

# The suites' lines stay within 80 columns, as the book's code does
# (tests/.clang-format formats them so).
check-test-width:
	@if awk 'length($$0) > 80 { print FILENAME ":" FNR ": " length($$0) " columns"; bad = 1 } END { exit !bad }' \
	    tests/*.c tests/*.h; then exit 1; fi
	@echo "no line of tests/ is wider than 80 columns: ok"

# No temporary file is tracked (outside a git checkout there is nothing to
# check).
check-stray:
	@if git rev-parse --git-dir >/dev/null 2>&1; then \
	  stray=$$(git ls-files | grep -E '\.tmp$$|~$$|\.tmp-[^/]*$$'); \
	  if [ -n "$$stray" ]; then echo "temporary files are tracked: $$stray"; exit 1; fi; \
	  echo "no temporary file is tracked: ok"; fi

# What runs the programs. The sanitized pass (make SAN=1 test) runs these
# alone: the other checks read text, charts and the workbook's own build,
# which the sanitizers do not change, and the first pass has checked them.
# Nor does it draw the figures again only to compare them: check-commands
# draws every figure's scene with the sanitized programs all the same.
PROGRAM_TESTS := test-tangle $(foreach n,$(NUMS),test-ch$(n)) \
                 $(if $(SAN),,check-figures) check-failures check-diagrams \
                 check-lines check-commands
BOOK_TESTS := benches check-src check-charts check-book check-map check-stray \
              check-allocations check-test-width check-quotes check-workbook \
              check-handout check-handout-page check-page check-build-speed \
              check-brackets check-weave-errors check-reuse
ifeq ($(HANDOUT),)
test: deps $(PROGRAM_TESTS) $(if $(SAN),,$(BOOK_TESTS))
	@# the book is up to date by now (check-book): -o keeps it so
	$(if $(SAN),,@$(MAKE) --no-print-directory -o build/book.html check-code-width)
	@echo "make test: all passed"
else
# A handout's tests: every chapter's suites against its program.
test: deps $(foreach n,$(NUMS),test-ch$(n))
	@echo "make test: all passed"
endif

clean:
	rm -rf build bin

