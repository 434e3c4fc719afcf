#!/bin/sh
# page_check.sh -- the book's scenes rendered in the book's own page, in
# headless Chromium, against the programs' PNGs (tools/checks/page_check.js):
#
#     sh tools/checks/page_check.sh BOOK.html BIN_DIR SIZE NN...
#
# For each chapter NN: every scene the chapter shows, and its empty scene,
# drawn by BIN_DIR/chNN at --size SIZE as references; then, in the page,
# the same renders (each within 1 code a channel), a scene with a mistake
# (the program's own located error, as bin/chNN wrote it), a mistake in
# --pixel (the option's, not the scene's), a render of some seconds (its
# progress shown while it runs, none left under it), a long render
# cancelled, and no request outside the file; and, in the same load of
# the page, make book-check's layout check at 1280 x 900
# (tools/checks/book_check.js). Where Chromium is installed but node is
# not, or the page has no programs, the layout is checked alone
# (tools/checks/book_check.sh); skipped, with status 0, without Chromium.
#
#     sh tools/checks/page_check.sh --scenes BOOK.html BIN_DIR SIZE NN:SCENE...
#
# renders only the scenes named (scenes/chNN-NAME.scene, as the chapter
# shows it) against BIN_DIR/chNN's, and the first one's chapter's empty
# scene against the first one's picture (the comparison must fail), with
# no request outside the file (make check-handout-page, on a handout's
# book).
#
#     sh tools/checks/page_check.sh --speed CSV ROUNDS BOOK.html BIN_DIR SIZE NN...
#   (PAGE_SPEED_CLANG_BIN=DIR: the same programs built by clang, the page's
#   compiler, timed beside them)
#
# measures instead: each chapter's own scene at --size SIZE, its render on
# one thread by BIN_DIR/chNN and in the page, ROUNDS times, into CSV (make
# chart-ch13_page; it fails without Chromium or the programs).
set -u
speed="" scenes=""
if [ "${1:-}" = "--speed" ]; then speed=$2 rounds=$3; shift 3; fi
if [ "${1:-}" = "--scenes" ]; then scenes=yes; shift; fi
if [ "$#" -lt 4 ]; then
  echo "usage: $0 [--speed CSV ROUNDS | --scenes] BOOK.html BIN_DIR SIZE NN... (NN:SCENE... with --scenes)" >&2
  exit 2
fi
book=$1 bin=$2 size=$3
shift 3
tools_dir=$(cd "$(dirname "$0")" && pwd)
. "$tools_dir/../editions/find_chromium.sh"
browser=$(find_chromium)
# skip WHY: the check cannot run here; a measurement must; the layout
# is checked alone where it can be.
skip() {
  if [ -n "$speed" ]; then echo "page-speed: error: $1" >&2; exit 1; fi
  echo "page-check: skipped: $1"
  [ -n "$scenes" ] || [ -z "$browser" ] || exec sh "$tools_dir/book_check.sh" --no-install "$book" -
  exit 0
}
if [ -z "$browser" ] || ! command -v node >/dev/null 2>&1; then
  skip "no chromium or no node (make book-check installs Chromium)"
fi
grep -q 'id="rt-program-' "$book" ||
  skip "the page has no programs (no clang for wasm32-wasi)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$(pwd)

if [ -n "$speed" ]; then
  chapters=$(printf '"%s",' "$@")
  machine="# machine: $(sed -n 's/^model name[^:]*: *//p' /proc/cpuinfo | head -n 1), \
$(nproc) CPUs (load $(cut -d ' ' -f 1 /proc/loadavg)); \
$(cc --version | head -n 1 | sed 's/ (.*)//') -O2 -g against $(clang --version | head -n 1 | \
  sed 's/ (.*//') --target=wasm32-wasi -O2 in $("$browser" --version 2>/dev/null | awk '{print $1, $2; exit}'); \
$(date -u '+%Y-%m-%d %H:%M UTC')"
  printf '{"speed": {"bin": "%s", "clangBin": "%s", "chapters": [%s], "size": "%s", "rounds": %s, "csv": "%s", "machine": "%s"}}\n' \
    "$bin" "${PAGE_SPEED_CLANG_BIN:-}" "${chapters%,}" "$size" "$rounds" "$work/speed.csv" "$machine" > "$work/cases.json"
  node "$tools_dir/page_check.js" "$browser" "$book" "$work/cases.json" || exit 1
  mv "$work/speed.csv" "$speed"
  exit 0
fi

# case_json NN SCENE: one render's case, SCENE empty for the empty scene.
case_json() {
  (cd "build/tangle/ch$1" &&
   if [ -n "$2" ]; then "$root/$bin/ch$1" "$2" --size "$size" -o "$work/ref.png"
   else : > "$work/empty.scene" &&
        "$root/$bin/ch$1" "$work/empty.scene" --size "$size" -o "$work/ref.png"; fi) \
    > /dev/null 2>&1 || { echo "page-check: error: $bin/ch$1 failed on '$2'" >&2; exit 1; }
  printf '{"chapter": "%s", "scene": "%s", "size": "%s", "reference": "%s"}' \
    "$1" "$2" "$size" "$(base64 -w 0 "$work/ref.png")"
}

# With --scenes: the scenes named, and the control.
if [ -n "$scenes" ]; then
  {
    printf '{"renders": [\n'
    sep=""
    for named in "$@"; do
      printf '%s' "$sep"; case_json "${named%%:*}" "${named#*:}" || exit 1; sep=",
"
    done
    printf '],\n"control": '
    case_json "${1%%:*}" "${1#*:}" | sed 's/"scene": "[^"]*"/"scene": ""/' || exit 1
    printf '}\n'
  } > "$work/cases.json" || exit 1
  node "$tools_dir/page_check.js" "$browser" "$book" "$work/cases.json"
  exit
fi

{
  printf '{"renders": [\n'
  sep=""
  for n in "$@"; do
    for scene in "" $(cd "build/tangle/ch$n" && ls scenes/ch"$n"-*.scene 2>/dev/null); do
      printf '%s' "$sep"; case_json "$n" "$scene" || exit 1; sep=",
"
    done
  done
  printf '],\n'
  # The comparison must be able to fail: chapter 2's empty scene against
  # the first scene chapter 2 shows (the scene's background alone, against
  # its spheres).
  printf '"control": '
  control=$(cd build/tangle/ch02 && ls scenes/ch02-*.scene | head -n 1)
  case_json 02 "$control" | sed 's/"scene": "[^"]*"/"scene": ""/' || exit 1
  printf ',\n'
  # A mistake in chapter 2's empty scene, the program's line as it writes it.
  mkdir -p "$work/mistake/scenes"
  printf 'camera fov 60\nsphere center 0 0 5 radius banana\n' > "$work/mistake/scenes/yours.scene"
  expected=$(cd "$work/mistake" && "$root/$bin/ch02" scenes/yours.scene -o out.png 2>&1 >/dev/null)
  printf '"mistake": {"chapter": "02", "text": "camera fov 60\\nsphere center 0 0 5 radius banana\\n", "expected": "%s"},\n' "$expected"
  last=$(echo "$@" | tr ' ' '\n' | tail -n 1)
  # A mistake in the last chapter's --pixel, the program's line as it
  # writes it, for a scene with none.
  printf 'sphere center 0 0 5 radius 1\n' > "$work/mistake/scenes/good.scene"
  expected=$(cd "$work/mistake" && "$root/$bin/ch$last" scenes/good.scene --pixel 'samples 3' -o out.png 2>&1 >/dev/null)
  printf '"pixelMistake": {"chapter": "%s", "text": "sphere center 0 0 5 radius 1\\n", "pixel": "samples 3", "expected": "%s"},\n' "$last" "$expected"
  # Seconds of work on one thread, its progress shown while it runs.
  printf '"progress": {"chapter": "%s", "size": "1200x900", "pixel": "pattern grid samples 16", "text": "sphere center 0 0 5 radius 1\\n"},\n' "$last"
  # Minutes of work on one thread: 4000 x 3000 pixels, 16 rays each.
  printf '"long": {"chapter": "%s", "size": "4000x3000", "pixel": "pattern grid samples 16", "text": "sphere center 0 0 5 radius 1\\n"},\n' "$last"
  # The layout at a reader's 1280 x 900, measured before any render.
  printf '"layout": {"script": "%s", "width": 1280, "height": 900}}\n' "$tools_dir/book_check.js"
} > "$work/cases.json" || exit 1

node "$tools_dir/page_check.js" "$browser" "$book" "$work/cases.json"
