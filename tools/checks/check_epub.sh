#!/bin/sh
# check_epub.sh -- the EPUB is a whole zip, its navigation lists every
# chapter, and epubcheck finds no error in it.
#
# Usage: tools/checks/check_epub.sh BOOK.epub CHAPTER.md...   (make check-epub)
# unzip must find no damaged entry, the first entry must be the file
# "mimetype" holding application/epub+zip (what readers look at first),
# and the navigation document (EPUB/nav.xhtml) must link to each chapter's
# id ({#chNN} on its first heading). Then, where epubcheck is installed
# (make installs it: tools/book/deps.sh), it must report 0 fatal errors and 0
# errors (warnings are shown, not counted); where it is not, the script
# says it skipped that part. Exits 1 with the reason otherwise.
set -u
epub=$1
shift
unzip -tq "$epub" > /dev/null 2>&1 || { echo "check-epub: $epub is not a whole zip"; exit 1; }
first=$(unzip -Z1 "$epub" | head -n 1)
[ "$first" = mimetype ] && [ "$(unzip -p "$epub" mimetype)" = "application/epub+zip" ] ||
    { echo "check-epub: $epub does not start with its mimetype"; exit 1; }
nav=$(unzip -p "$epub" EPUB/nav.xhtml 2> /dev/null) ||
    { echo "check-epub: $epub has no EPUB/nav.xhtml"; exit 1; }
for chapter in "$@"; do
    id=$(sed -n '1,/^# /s/^# .*{#\([^} ]*\).*/\1/p' "$chapter" | head -n 1)
    echo "$nav" | grep -q "href=\"[^\"]*#$id\"" ||
        { echo "check-epub: the navigation of $epub does not list $chapter (#$id)"; exit 1; }
done
echo "check-epub: $epub: a whole zip whose navigation lists all $# chapters"

# Debian's /usr/bin/epubcheck is the jar itself, which runs as a command
# only where the kernel knows jars (binfmt_misc): java runs it everywhere.
checker=$(command -v epubcheck) || {
    echo "check-epub: epubcheck skipped: not installed (make installs it as root; apt-get install epubcheck)"
    exit 0
}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# --locale en: the summary read below is in English whatever the machine's.
# Java's quick compiler alone and one garbage collector thread: the same
# time on the clock for half the processor time, which make test's other
# jobs use.
if [ "$(dd if="$checker" bs=2 count=1 2> /dev/null)" = PK ]; then
    java -XX:TieredStopAtLevel=1 -XX:+UseSerialGC -jar "$checker" --locale en "$epub" > "$log" 2>&1
else
    "$checker" --locale en "$epub" > "$log" 2>&1
fi
# "Messages: 0 fatals / 3 errors / 0 warnings / 0 infos"
counts=$(sed -n 's/^Messages: \([0-9]*\) fatals* \/ \([0-9]*\) errors* .*/\1 \2/p' "$log")
if [ -z "$counts" ]; then
    echo "check-epub: epubcheck did not finish:"
    tail -n 5 "$log"
    exit 1
fi
# shellcheck disable=SC2086  # two numbers, split on purpose
set -- $counts
grep '^WARNING' "$log" | head -n 5
if [ "$1" != 0 ] || [ "$2" != 0 ]; then
    { grep '^FATAL' "$log"; grep '^ERROR' "$log"; } | head -n 20
    echo "check-epub: epubcheck: $epub has $1 fatal errors and $2 errors (the first are above)"
    exit 1
fi
echo "check-epub: epubcheck: $epub has no error"
