# book_code.awk -- an exercise's functions as a handout calls the book's
# compiled code through them.
#
# A library for tools/workbook/workbook.awk (awk -f tools/workbook/stub.awk -f
# tools/workbook/book_code.awk -f tools/workbook/workbook.awk -v mode=...), after
# tools/stub.awk. A handout holds no exercise's code, only its stub; the
# book's code of every exercise is shipped compiled (tools/workbook/book_code.sh),
# and a student who has not started an exercise gets the book's behaviour
# all the same, through three forms of the exercise's code:
#
#   forward  (the student's program, for an exercise not started): each
#            function's body calls the book's compiled function,
#            rt_book_NAME, with the same arguments;
#   export   (the student's program, every exercise, appended after the
#            student's own code): a function rt_wb_NAME that calls NAME,
#            so that the book's compiled code can call the student's;
#   book     (the book's code, compiled when the handout is made): each
#            function NAME is renamed rt_book_NAME, keeping its body, and
#            NAME itself calls rt_wb_NAME, so that the book's code of one
#            exercise calls the student's code of another (and the
#            book's, through its forward form, when not started).
#
# The names of a function of a .c file hold the file's name (the macro
# RT_TU, which the build defines as the file's name: a chunk compiled in
# two files, in double and in float, gives two); those of a static inline
# function of a header are the same in every file (rt_book_h_NAME), weak,
# each file's copy as good as another's. Comments, types, tables and
# <<chunk>> lines between functions are kept as they are; a <<chunk>> line
# in a function's body is kept in the book form, and in the forward form
# under "#if 0" (its code is in the book's compiled body).

# The parts of a function's signature SIG (one line):
# bc_head (storage and return type), bc_name (as written: NAME or
# MACRO(NAME)), bc_inner (NAME), bc_params (inside the parentheses),
# bc_args (the parameters' names, comma-separated), bc_type (the return
# type without storage), bc_void (it returns nothing).
function bc_parse(sig,    close_at, depth, i, c, open_at, head, np, parts,
                  k, p, name, sep) {
    sub(/[ \t]*\{.*$/, "", sig)
    sub(/[ \t]+$/, "", sig)
    # the parameter list: the parentheses that end the signature
    close_at = length(sig)
    depth = 0
    for (i = close_at; i > 0; i--) {
        c = substr(sig, i, 1)
        if (c == ")") depth++
        if (c == "(" && --depth == 0) { open_at = i; break }
    }
    bc_params = substr(sig, open_at + 1, close_at - open_at - 1)
    head = substr(sig, 1, open_at - 1)
    sub(/[ \t]+$/, "", head)
    if (head ~ /\)$/) { # MACRO(NAME)
        match(head, /[A-Za-z_][A-Za-z_0-9]*[ \t]*\([ \t]*[A-Za-z_][A-Za-z_0-9]*[ \t]*\)$/)
        bc_name = substr(head, RSTART)
        bc_inner = bc_name
        sub(/^[^(]*\([ \t]*/, "", bc_inner)
        sub(/[ \t]*\)$/, "", bc_inner)
    } else {
        match(head, /[A-Za-z_][A-Za-z_0-9]*$/)
        bc_name = bc_inner = substr(head, RSTART)
    }
    bc_head = substr(head, 1, length(head) - length(bc_name))
    bc_type = " " bc_head " "
    while (sub(/[ \t](static|inline|extern)[ \t]/, " ", bc_type))
        ;
    gsub(/^[ \t]+|[ \t]+$/, "", bc_type)
    bc_void = bc_type == "void"
    # the arguments: each parameter's name
    bc_args = ""
    np = 0
    depth = 0
    p = ""
    for (i = 1; i <= length(bc_params); i++) {
        c = substr(bc_params, i, 1)
        if (c == "(" || c == "[") depth++
        if (c == ")" || c == "]") depth--
        if (c == "," && depth == 0) { parts[++np] = p; p = ""; continue }
        p = p c
    }
    parts[++np] = p
    sep = ""
    for (k = 1; k <= np; k++) {
        p = parts[k]
        gsub(/^[ \t]+|[ \t]+$/, "", p)
        if (p == "void" || p == "")
            continue
        if (match(p, /\([ \t]*\*[ \t]*[A-Za-z_][A-Za-z_0-9]*/)) {
            name = substr(p, RSTART, RLENGTH)
            sub(/^\([ \t]*\*[ \t]*/, "", name)
        } else {
            sub(/[ \t]*\[[^]]*\][ \t]*$/, "", p)
            while (sub(/[ \t]*\[[^]]*\][ \t]*$/, "", p))
                ;
            match(p, /[A-Za-z_][A-Za-z_0-9]*$/)
            name = substr(p, RSTART, RLENGTH)
        }
        bc_args = bc_args sep name
        sep = ", "
    }
}

# The names the two sides give the function just parsed.
function bc_book_name(header) {
    return header ? "rt_book_h_" bc_inner : "RT_BOOK(" bc_inner ")"
}
function bc_wb_name(header) {
    return header ? "rt_wb_h_" bc_inner : "RT_WB(" bc_inner ")"
}

# "TYPE CALLEE(PARAMS)" with the head's storage dropped: a declaration.
function bc_declaration(callee, weak) {
    return (weak ? "__attribute__((weak)) " : "") bc_type " " callee \
           "(" bc_params ")"
}

# A body that calls CALLEE with the function's own arguments (the
# callee in parentheses, as no line of the book writes a call).
function bc_call_body(callee) {
    return "{ " (bc_void ? "" : "return ") "(" callee ")(" bc_args "); }"
}

# The macros that name the two sides' functions in a .c file (RT_TU, the
# file's name, comes from the build's -DRT_TU=...).
function bc_macros() {
    return "#ifndef RT_BOOK\n" \
           "#define RT_GLUE_(a, b, c) a##b##_##c\n" \
           "#define RT_GLUE(a, b, c) RT_GLUE_(a, b, c)\n" \
           "#define RT_BOOK(name) RT_GLUE(rt_book_, RT_TU, name)\n" \
           "#define RT_WB(name) RT_GLUE(rt_wb_, RT_TU, name)\n" \
           "#endif\n"
}

# The function whose signature lines are SIG_TEXT (joined by blanks in
# SIG) and whose body lines are BODY ("" for a function on one line, its
# body then in ONE_LINE_BODY), in the form MODE.
function bc_function(sig_text, sig, body, one_line_body, mode, header,
                     chunks, n, i, lines, out, renamed) {
    bc_parse(sig)
    if (mode == "forward") {
        out = bc_declaration(bc_book_name(header)) ";\n"
        out = out "__attribute__((unused)) " bc_head bc_name "(" bc_params ")\n" \
              bc_call_body(bc_book_name(header)) "\n"
        chunks = ""
        n = split(body, lines, "\n")
        for (i = 1; i <= n; i++)
            if (lines[i] ~ /^[ \t]+<<[^>]+>>[ \t]*$/)
                chunks = chunks lines[i] "\n"
        if (chunks != "")
            out = out "#if 0 /* in the book's compiled body */\n" chunks "#endif\n"
        return out
    }
    if (mode == "export")
        return bc_declaration(bc_wb_name(header), header) ";\n" \
               bc_declaration(bc_wb_name(header), header) "\n" \
               bc_call_body(bc_name) "\n"
    # book: NAME calls the student's program; the book's body is renamed
    out = bc_declaration(bc_wb_name(header)) ";\n"
    out = out "__attribute__((unused)) " bc_head bc_name "(" bc_params ")\n" \
          bc_call_body(bc_wb_name(header)) "\n"
    renamed = bc_declaration(bc_book_name(header), header)
    if (body == "")
        return out renamed " " one_line_body "\n"
    return out renamed "\n" body
}

# CODE (an exercise's chunk, lines separated by "\n") in the form MODE
# (forward, export or book; see above); HEADER: the chunk is in a header.
function book_form(code, mode, header,    lines, n, i, out, depth, sig,
                   sig_text, in_body, line, body, one) {
    # a fragment of a body has no function to call the book's through:
    # the handout gets its stub, not its code
    if (mode == "forward" && stub_is_fragment(code))
        return stub_of(code)
    n = split(code, lines, "\n")
    out = header ? "" : bc_macros()
    depth = 0
    in_body = 0
    sig = sig_text = ""
    for (i = 1; i <= n; i++) {
        line = lines[i]
        if (in_body) {
            body = body line "\n"
            depth += stub_braces(line)
            if (depth == 0) {
                in_body = 0
                out = out bc_function(sig_text, sig, body, "", mode, header)
                sig = sig_text = ""
            }
            continue
        }
        if (depth == 0 && line ~ /^[A-Za-z_].*\(/ && line !~ /;[ \t]*$/ && sig == "") {
            sig = line
            sig_text = line "\n"
            if (line ~ /\)[ \t]*\{.*\}[ \t]*$/) { # the whole function
                one = line
                sub(/^[^{]*/, "", one)
                out = out bc_function(sig_text, sig, "", one, mode, header)
                sig = sig_text = ""
            }
            continue
        }
        if (sig != "" && depth == 0 && line ~ /^\{[ \t]*$/) {
            body = line "\n"
            depth = 1
            in_body = 1
            continue
        }
        if (sig != "") { # the signature goes on
            sig = sig " " line
            sig_text = sig_text line "\n"
            gsub(/[ \t]+/, " ", sig)
            if (line ~ /;[ \t]*$/) { # a declaration after all
                if (mode != "export")
                    out = out sig_text
                sig = sig_text = ""
            }
            continue
        }
        depth += stub_braces(line)
        if (mode != "export")
            out = out line "\n"
    }
    sub(/\n$/, "", out)
    return out
}
