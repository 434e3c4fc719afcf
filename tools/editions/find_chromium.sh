# find_chromium.sh: sourced by the scripts that drive the browser
# (book_check.sh, pdf.sh). find_chromium prints the browser's command, or
# nothing when none is installed.
find_chromium() {
    for name in chromium chromium-browser google-chrome; do
        if command -v "$name" >/dev/null 2>&1; then echo "$name"; return; fi
    done
}
