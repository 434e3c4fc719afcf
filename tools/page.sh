#!/bin/sh
# page.sh -- what the book's page needs to render its scenes, as HTML to
# put before its </body> (tools/weave.sh does, given WEAVE_PAGE):
#
#     sh tools/page.sh OUT.html PROGRAM.wasm... -- MESH.obj...
#
# Each program build/wasm/chNN.wasm and each mesh goes in gzip'd (gzip -n:
# the same bytes every time) and base64'd, in a script element the browser
# does not run; then the worker's code, the style and tools/page/playground.js.
# Everything is in the one file: the page fetches nothing.
set -eu
if [ "$#" -lt 2 ]; then
  echo "usage: $0 OUT.html PROGRAM.wasm... -- MESH.obj..." >&2
  exit 2
fi
out=$1
shift
page_dir=$(cd "$(dirname "$0")" && pwd)/page
tmp="$out.tmp"
{
  echo '<style>'
  cat "$page_dir/playground.css"
  echo '</style>'
  meshes=no
  for f in "$@"; do
    if [ "$f" = -- ]; then meshes=yes; continue; fi
    name=$(basename "$f")
    if [ "$meshes" = yes ]; then
      printf '<script type="application/octet-stream" class="rt-mesh" data-name="%s">\n' "$name"
    else
      printf '<script type="application/octet-stream" id="rt-program-%s">\n' \
        "$(echo "$name" | sed 's/^ch\([0-9]*\)\.wasm$/\1/')"
    fi
    gzip -9 -n -c "$f" | base64 -w 76
    echo '</script>'
  done
  echo '<script type="text/plain" id="rt-worker">'
  cat "$page_dir/worker.js"
  echo '</script>'
  echo '<script>'
  cat "$page_dir/playground.js"
  echo '</script>'
} > "$tmp"
mv "$tmp" "$out"
