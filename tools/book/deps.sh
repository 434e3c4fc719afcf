#!/bin/sh
# Installs what the build needs when it is missing, or says how to.
# Run by `make` before anything is compiled. Debian and Ubuntu: apt-get,
# as root or with passwordless sudo; anywhere else it prints the command.
# Extra packages can be asked for by name: `sh tools/book/deps.sh clang`.
# `sh tools/book/deps.sh --page` asks only for what compiles the programs for
# the book's page (WebAssembly: Clang, its linker, wasi-libc and its
# builtins), wanted rather than needed: the Makefile asks for them before
# it looks for them, and builds the book without its playground if they
# cannot be installed.
# Wanted, not needed: epubcheck (make test checks the EPUB with it where it
# is installed, and says it skipped the check where it is not) is
# installed with the others when apt-get can, and its absence, or an
# apt-get that cannot fetch it (no network), never stops the build; a
# failed attempt is remembered in build/deps-wanted.failed, so that it is
# not made again by every make (make clean forgets it).

missing=""
need() { missing="$missing $1"; }
wanted=""
want() { wanted="$wanted $1"; }

if [ "${1:-}" = "--page" ]; then
  printf 'int main(void) { return 0; }\n' |
    clang --target=wasm32-wasi -x c - -o /dev/null >/dev/null 2>&1 && exit 0
  for p in clang lld wasi-libc libclang-rt-dev-wasm32; do want "$p"; done
  shift
  failed_wanted=build/deps-page.failed
  [ -f "$failed_wanted" ] && [ "$(cat "$failed_wanted")" = "$wanted" ] && exit 0
  missing="" # only these, whatever else is missing: the build asks later
else
command -v pkg-config >/dev/null 2>&1 || need pkg-config
command -v cc >/dev/null 2>&1 || need gcc
if command -v pkg-config >/dev/null 2>&1; then
  pkg-config --exists libpng || need libpng-dev
  pkg-config --exists check || need check
else
  need libpng-dev; need check
fi
# A handout (book/MACHINE: tools/workbook/book_code.sh) comes with its book woven:
# it builds and grades the programs, and needs no more than the above.
if [ ! -f book/MACHINE ]; then
command -v pandoc >/dev/null 2>&1 || need pandoc
command -v gnuplot >/dev/null 2>&1 || need gnuplot-nox
command -v unzip >/dev/null 2>&1 || need unzip # make test reads the EPUB
command -v zip >/dev/null 2>&1 || need zip     # tools/editions/epub.sh writes it
command -v epubcheck >/dev/null 2>&1 || want epubcheck
fi
failed_wanted=build/deps-wanted.failed
[ -f "$failed_wanted" ] && [ "$(cat "$failed_wanted")" = "$wanted" ] && wanted=""
fi
for extra in "$@"; do
  dpkg -s "$extra" >/dev/null 2>&1 || need "$extra"
done

[ -z "$missing$wanted" ] && exit 0

if ! command -v apt-get >/dev/null 2>&1; then
  [ -z "$missing" ] && exit 0
  echo "deps: missing:$missing" >&2
  echo "deps: install them with your package manager; see README.md (Requirements)" >&2
  exit 1
fi
if [ "$(id -u)" = 0 ]; then
  sudo=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  sudo="sudo"
else
  [ -z "$missing" ] && exit 0
  echo "deps: missing:$missing" >&2
  echo "deps: run this once, then make again:" >&2
  echo "    sudo apt-get install -y$missing$wanted" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
if [ -n "$wanted" ]; then
  echo "deps: installing$wanted"
  $sudo apt-get install -y -q --no-install-recommends $wanted >/dev/null 2>&1 || {
    $sudo apt-get update -q >/dev/null 2>&1 &&
    $sudo apt-get install -y -q --no-install-recommends $wanted >/dev/null 2>&1
  } || {
    echo "deps: could not install$wanted; make test skips what needs it" >&2
    mkdir -p "$(dirname "$failed_wanted")" && echo "$wanted" > "$failed_wanted"
  }
fi
[ -z "$missing" ] && exit 0
echo "deps: installing$missing"
# Install first from the lists the machine has; refresh them only if that fails.
$sudo apt-get install -y --no-install-recommends $missing >/dev/null 2>&1 || {
  $sudo apt-get update -q >/dev/null &&
  $sudo apt-get install -y -q --no-install-recommends $missing
} || { echo "deps: apt-get install$missing failed" >&2; exit 1; }
