#!/bin/sh
# page.sh -- what the book's page needs to render its scenes, as HTML to
# put before its </body> (tools/book/weave.sh does, given WEAVE_PAGE):
#
#     sh tools/editions/page.sh OUT.html chNN.wasm.b64... -- MESH.obj.b64...
#
# Each program (build/wasm/chNN.wasm) and each mesh, gzip'd and in base64
# (the Makefile makes the .b64 files), goes in a script element that the
# browser does not run; then the worker's code, the style and
# tools/editions/page/playground.js.
# Everything is in the one file: the page fetches nothing.
set -eu
if [ "$#" -lt 2 ]; then
  echo "usage: $0 OUT.html chNN.wasm.b64... -- MESH.obj.b64..." >&2
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
    name=$(basename "$f" .b64)
    if [ "$meshes" = yes ]; then
      printf '<script type="application/octet-stream" class="rt-mesh" data-name="%s">\n' "$name"
    else
      printf '<script type="application/octet-stream" id="rt-program-%s">\n' \
        "$(echo "$name" | sed 's/^ch\([0-9]*\)\.wasm$/\1/')"
    fi
    cat "$f"
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
