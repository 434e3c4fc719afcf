#!/bin/sh
# check_epub.sh -- the EPUB is a whole zip, and its navigation lists every
# chapter.
#
# Usage: tools/check_epub.sh BOOK.epub CHAPTER.md...   (make check-epub)
# unzip must find no damaged entry, the first entry must be the file
# "mimetype" holding application/epub+zip (what readers look at first),
# and the navigation document (EPUB/nav.xhtml) must link to each chapter's
# id ({#chNN} on its first heading). Exits 1 with the reason otherwise.
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
