#!/bin/sh
# check_commands.sh -- run every chapter-binary command the book quotes.
#
# Usage: sh tools/checks/check_commands.sh [--root DIR] [--bin BINDIR] [FILE...]
#        sh tools/checks/check_commands.sh --self-test
#
# FILEs default to chapters/*.md, book.md and README.md. A quoted command is
# an inline code span (`...`, which may run over a line break) or a line of
# a fenced code block that begins with "bin/chNN " (a "$ " prompt before it
# is allowed; a shell comment after it is dropped). Commands with
# placeholders are usage lines, not commands, and are skipped: any of
# [ ] < > or "...", or a word in capitals (SCENE, OUT.png, WxH).
#
# Each command runs with sh in a scratch folder that links to every entry of
# the repository root DIR (default: the current folder), so relative paths
# such as src/ch01/scenes/ch01-wide.scene work, while "-o FILE" is rewritten
# to a file in the scratch folder and files a command creates stay there.
# With --bin, the scratch folder's bin/ is BINDIR instead (make SAN=1 test
# runs the commands with its sanitized build/san/bin).
# A command that exits non-zero is reported as "FILE:LINE: error: ..." with
# the end of its output; the script then exits 1. Otherwise it prints
#   check-commands: N commands quoted in M files ran: ok
#
# --self-test feeds the script a made-up book with a fake bin/ch01 (it fails
# when a file named on its command line does not exist): a wrong path must
# fail with its file:line, placeholders must be skipped, a span broken over
# two lines and a fenced command must run, and -o must be rewritten.
set -u

# extract FILE: "LINE<tab>COMMAND" for every quoted bin/chNN command.
extract() {
  awk '
    function emit(line, text) {
      sub(/[ \t]+#.*$/, "", text)            # a shell comment after it
      gsub(/[ \t]+/, " ", text); sub(/^ /, "", text); sub(/ $/, "", text)
      if (text ~ /^bin\/ch[0-9][0-9] /) printf "%d\t%s\n", line, text
    }
    # Inline spans: a run of n backticks opens a span that the next run of
    # exactly n backticks closes. open = 0 outside a span.
    function spans(text, line,    run) {
      while (text != "") {
        if (!match(text, /`+/)) { if (open) span = span text; return }
        run = RLENGTH
        if (open) span = span substr(text, 1, RSTART - 1)
        text = substr(text, RSTART + RLENGTH)
        if (!open) { open = run; span = ""; start = line }
        else if (run == open) { emit(start, span); open = 0 }
        else span = span substr("``````````````````", 1, run)
      }
    }
    /^[ \t]*(```|~~~)/ { fenced = !fenced; open = 0; next }
    fenced {
      text = $0; sub(/^[ \t]*(\$ )?/, "", text)
      if (text ~ /^bin\/ch[0-9][0-9] /) emit(NR, text)
      next
    }
    /^[ \t]*$/ { open = 0; next }     # a span never crosses a paragraph
    { spans($0, NR); if (open) span = span " " }
  ' "$1"
}

# A usage line rather than a command: placeholders in it.
has_placeholder() {
  printf '%s\n' "$1" | grep -Eq '[][<>]|\.\.\.|[A-Z][A-Z]|[A-Z]x[A-Z]'
}

# The command with "-o PATH" pointing into the folder $1 instead.
redirect_output() {
  printf '%s\n' "$2" | sed "s| -o \([^ ]*/\)\{0,1\}\([^ /]*\)| -o $1/\2|g"
}

# make_scratch ROOT BINDIR: a new folder linking to every entry of ROOT,
# with bin/ linking to BINDIR if it is given; prints its path.
make_scratch() {
  scratch=$(mktemp -d) || exit 2
  for entry in "$1"/* "$1"/.[!.]*; do
    [ -e "$entry" ] && ln -s "$entry" "$scratch/"
  done
  if [ -n "$2" ]; then rm -f "$scratch/bin"; ln -s "$2" "$scratch/bin"; fi
  mkdir "$scratch/check-commands-out"
  echo "$scratch"
}

# list_file SCRATCH FILE: appends FILE's commands to SCRATCH/.commands as
# "FILE<tab>LINE<tab>COMMAND"; counts them in ran.
list_file() {
  extract "$2" > "$1/.one" || exit 2
  while IFS="$(printf '\t')" read -r line command; do
    if has_placeholder "$command"; then continue; fi
    ran=$((ran + 1))
    printf '%s\t%s\t%s\n' "$2" "$line" "$command" >> "$1/.commands"
  done < "$1/.one"
}

# run_one SCRATCH K: runs command K of SCRATCH/.commands there; its output
# goes to SCRATCH/.output.K, and SCRATCH/.failed.K is made if it fails.
run_one() {
  command=$(sed -n "$2{s/^[^\t]*\t[^\t]*\t//;p;q;}" "$1/.commands")
  rewritten=$(redirect_output "$1/check-commands-out" "$command")
  (cd "$1" && timeout 600 sh -c "$rewritten") > "$1/.output.$2" 2>&1 ||
    : > "$1/.failed.$2"
}

# run_all SCRATCH: every listed command, one a core at a time (each is a
# program of its own); the failures reported in the order of the list and
# counted in failed.
run_all() {
  cores=$(nproc 2>/dev/null || echo 2)
  k=0
  while [ "$k" -lt "$ran" ]; do k=$((k + 1)); echo "$k"; done |
    xargs -P "$cores" -I {} sh "$0" --run-one "$1" {}
  k=0
  while IFS="$(printf '\t')" read -r file line command; do
    k=$((k + 1))
    [ -e "$1/.failed.$k" ] || continue
    failed=$((failed + 1))
    echo "$file:$line: error: quoted command fails: $command" >&2
    tail -n 5 "$1/.output.$k" | sed 's/^/    /' >&2
  done < "$1/.commands"
}

# check ROOT BINDIR FILE...
check() {
  root=$(cd "$1" && pwd) || exit 2  # links must not be relative
  bin_dir=""
  if [ -n "$2" ]; then bin_dir=$(cd "$2" && pwd) || exit 2; fi
  shift 2
  scratch=$(make_scratch "$root" "$bin_dir")
  ran=0 failed=0
  : > "$scratch/.commands"
  for file in "$@"; do
    if [ ! -f "$file" ]; then
      echo "check-commands: error: no file $file" >&2; failed=$((failed + 1)); continue
    fi
    list_file "$scratch" "$file"
  done
  run_all "$scratch"
  rm -rf "$scratch"
  if [ "$failed" -gt 0 ]; then
    echo "check-commands: $failed of $ran quoted commands failed" >&2
    return 1
  fi
  echo "check-commands: $ran commands quoted in $# files ran: ok"
}

# A fake chapter binary for the self-test.
write_fake_binary() {
  mkdir -p "$1/bin"
  cat > "$1/bin/ch01" <<'EOF'
#!/bin/sh
while [ $# -gt 0 ]; do
  case $1 in
    -o) shift
        case $1 in */check-commands-out/*) ;; *) echo "-o not rewritten: $1"; exit 3 ;; esac ;;
    -*) ;;
    *) [ -f "$1" ] || { echo "no such file: $1"; exit 1; } ;;
  esac
  shift
done
EOF
  chmod +x "$1/bin/ch01"
}

# The backquotes in the made-up book are Markdown, not shell.
# shellcheck disable=SC2016
self_test() {
  dir=$(mktemp -d)
  write_fake_binary "$dir"
  echo "camera fov 90" > "$dir/good.scene"
  printf '%s\n' 'Run `bin/ch01 good.scene -o figures/x.png` first; then' \
    'the usage `bin/ch01 [SCENE] [-o OUT.png]` and `bin/ch01 SCENE` are skipped;' \
    'a span over two lines `bin/ch01' 'good.scene --stats` runs.' '' \
    '```sh' '$ bin/ch01 good.scene -o out.png' '```' > "$dir/good.md"
  cp "$dir/good.md" "$dir/bad.md"
  printf '%s\n' '' 'A wrong path: `bin/ch01 no/such.scene -o x.png`.' >> "$dir/bad.md"
  status=0
  if ! out=$(check "$dir" "" "$dir/good.md" 2>&1) ||
     ! echo "$out" | grep -q '^check-commands: 3 commands .*: ok$'; then
    echo "self-test: the 3 good commands did not all run and pass:"; echo "$out"; status=1
  fi
  if out=$(check "$dir" "" "$dir/bad.md" 2>&1); then
    echo "self-test: a wrong path did not fail"; status=1
  fi
  if ! echo "$out" | grep -q "bad.md:10: error: quoted command fails: bin/ch01 no/such"; then
    echo "self-test: the failure was not reported at bad.md:10:"; echo "$out"; status=1
  fi
  rm -rf "$dir"
  [ "$status" = 0 ] && echo "check-commands: self-test passed"
  return "$status"
}

if [ "${1:-}" = "--run-one" ]; then # a command of run_all's, in xargs
  run_one "$2" "$3"
  exit 0
fi
if [ "${1:-}" = "--self-test" ]; then
  self_test
  exit $?
fi
root=. bin=""
while [ "$#" -ge 2 ]; do
  case $1 in
    --root) root=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    *) break ;;
  esac
done
[ "$#" -gt 0 ] || set -- chapters/*.md book.md README.md
check "$root" "$bin" "$@"
