# stub.awk -- turn the code of an exercise into a stub that compiles.
#
# A library for other awk programs (awk -f tools/stub.awk -f PROGRAM):
# stub_of(CODE) returns CODE, lines separated by "\n", with the body of
# every function replaced by a comment and a return of zero: what is not a
# function body (comments, #include, types, prototypes, tables, <<chunk>>
# lines between functions) is kept, so that the stub declares what the
# book's code declares. The book writes a function's "{" alone at column 0,
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

function stub_of(code,    lines, n, i, out, depth, sig, in_body, line) {
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
                out = out "}\n"
            }
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
            out = out "{\n    " stub_return(stub_return_type(sig)) "\n"
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
