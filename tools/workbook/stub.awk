# stub.awk -- turn the code of an exercise into a stub that compiles.
#
# A library for other awk programs (awk -f tools/workbook/stub.awk -f PROGRAM):
# stub_of(CODE) returns CODE, lines separated by "\n", with the body of
# every function replaced by a comment and a return of zero: what is not a
# function body (comments, #include, types, prototypes, tables, <<chunk>>
# lines between functions) is kept, so that the stub declares what the
# book's code declares; a fragment of a body (stub_is_fragment) becomes a
# return of zero. A <<chunk>> line in a body stays too, so that the
# chapters that add to that chunk still find it: when the body returns a
# variable of its own, the stub declares it, zero, before the chunk lines. The book writes a function's "{" alone at column 0,
# or the whole function on one line; a body is what lies between that "{"
# and the "}" that closes it, found by counting braces outside strings,
# characters and comments.

# The return type of the function whose signature starts at SIG:
# what comes before the name in front of the first "(".
function stub_return_type(sig,    head) {
    head = sig
    sub(/\(.*/, "", head)
    sub(/[A-Za-z_][A-Za-z_0-9]*[ \t]*$/, "", head)
    head = " " head
    while (sub(/[ \t](static|inline|extern)[ \t]/, " ", head))
        ;
    gsub(/^[ \t]+|[ \t]+$/, "", head)
    return head
}

# The statement that stands for a body returning TYPE.
function stub_return(type) {
    if (type == "void" || type == "")
        return "/* your code here */"
    return "return (" type "){0}; /* your code here */"
}

# LINE without its strings, character constants and // comment.
function stub_code_part(line) {
    gsub(/\\./, "", line)
    gsub(/"[^"]*"/, "", line)
    gsub(/'[^']*'/, "", line)
    sub(/\/\/.*/, "", line)
    gsub(/\/\*([^*]|\*[^\/])*\*\//, "", line)
    return line
}

function stub_braces(line,    code, opens, closes) {
    code = stub_code_part(line)
    opens = gsub(/\{/, "{", code)
    closes = gsub(/\}/, "}", code)
    return opens - closes
}

# The last statement of the body, when it is "return NAME;": NAME.
function stub_returned_variable(    i) {
    for (i = stub_body_count; i > 0; i--) {
        if (stub_body_line[i] ~ /^[ \t]*(\}[ \t]*)?$/)
            continue
        if (match(stub_body_line[i], /^[ \t]+return [A-Za-z_][A-Za-z_0-9]*;/))
            return substr(stub_body_line[i], RSTART, RLENGTH)
        return ""
    }
    return ""
}

# "TYPE NAME" from the body's declaration of NAME, or "".
function stub_declaration_of(name,    i, line) {
    for (i = 1; i <= stub_body_count; i++) {
        line = stub_body_line[i]
        if (line ~ /^[ \t]+return[ \t]/)
            continue
        if (line ~ ("^[ \t]+[A-Za-z_][A-Za-z_0-9]*[ \t*]+" name "[ \t]*(=|;)")) {
            sub("[ \t]*(=|;).*", "", line)
            sub(/^[ \t]+/, "", line)
            return line
        }
    }
    return ""
}

# The stub of the body just read, for a function returning TYPE.
function stub_body(type,    i, chunks, name, declared) {
    chunks = ""
    for (i = 1; i <= stub_body_count; i++)
        if (stub_body_line[i] ~ /^[ \t]+<<[^>]+>>[ \t]*$/)
            chunks = chunks stub_body_line[i] "\n"
    if (chunks == "")
        return "    " stub_return(type) "\n"
    name = stub_returned_variable()
    sub(/^[ \t]+return /, "", name)
    sub(/;$/, "", name)
    declared = name == "" ? "" : stub_declaration_of(name)
    if (declared == "")
        return chunks "    " stub_return(type) "\n"
    return "    " declared " = {0}; /* your code here */\n" chunks \
           "    return " name ";\n"
}

# A function's body in pieces, not a function (statements at column 0 that
# return, as a chunk that the book includes inside a function): its stub
# is a return of zero.
function stub_is_fragment(code) {
    return code ~ /(^|\n)return[ \t;(]/
}

function stub_of(code,    lines, n, i, out, depth, sig, in_body, line, type) {
    if (stub_is_fragment(code))
        return "return 0; /* your code here */"
    n = split(code, lines, "\n")
    out = ""
    depth = 0
    in_body = 0
    sig = ""
    for (i = 1; i <= n; i++) {
        line = lines[i]
        if (in_body) {
            depth += stub_braces(line)
            if (depth == 0) {
                in_body = 0
                out = out stub_body(type) "}\n"
            } else
                stub_body_line[++stub_body_count] = line
            continue
        }
        if (depth == 0 && line ~ /^[A-Za-z_].*\(/ && line !~ /;[ \t]*$/ && sig == "")
            sig = line
        if (depth == 0 && line ~ /^[A-Za-z_].*\)[ \t]*\{.*\}[ \t]*$/) {
            sub(/\{.*/, "", line)
            out = out line "{ " stub_return(stub_return_type(sig)) " }\n"
            sig = ""
            continue
        }
        if (depth == 0 && line ~ /^\{[ \t]*$/ && sig != "") {
            out = out "{\n"
            type = stub_return_type(sig)
            stub_body_count = 0
            in_body = 1
            depth = 1
            sig = ""
            continue
        }
        depth += stub_braces(line)
        if (depth == 0 && (line ~ /;[ \t]*$/ || line ~ /^[ \t]*$/ || line ~ /\}/))
            sig = ""
        out = out line "\n"
    }
    sub(/\n$/, "", out)
    return out
}
