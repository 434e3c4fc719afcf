# test_index.awk -- where each test of the suites is, and its time limit.
#
#   awk -f tools/workbook/test_index.awk tests/chNN_*.c...
#
# prints one line per test, tab-separated: NAME FILE LINE LIMIT, where
# FILE:LINE is its START_TEST and LIMIT the seconds its test case sets
# (tcase_set_timeout), or 0 for Check's default. The grader names a test
# that timed out by these, not by the last place it checked something.

FNR == 1 { delete limit_of; delete case_of }
/^START_TEST\(/ {
    name = $0
    sub(/^START_TEST\([ \t]*/, "", name)
    sub(/[ \t]*\).*/, "", name)
    file_of[name] = FILENAME
    line_of[name] = FNR
    order[++count] = name
}
# TCase *v = tcase_create("..."); tcase_set_timeout(v, N);
/tcase_set_timeout\(/ {
    v = $0
    sub(/.*tcase_set_timeout\([ \t]*/, "", v)
    n = v
    sub(/[ \t]*,.*/, "", v)
    sub(/^[^,]*,[ \t]*/, "", n)
    sub(/[ \t]*\).*/, "", n)
    limit_of[FILENAME, v] = n + 0
}
# tcase_add_..._test(v, name) or tcase_add_..._test(v,\n name), or
# tcase_add_..._test(\n v, name)
/tcase_add_[a-z_]*test[ \t]*\(/ {
    call = $0
    while (call !~ /\)/ && (getline more) > 0)
        call = call " " more
    sub(/.*tcase_add_[a-z_]*test[ \t]*\([ \t]*/, "", call)
    v = call
    sub(/[ \t]*,.*/, "", v)
    t = call
    sub(/^[^,]*,[ \t]*/, "", t)
    sub(/[ \t]*[,)].*/, "", t)
    case_of[t] = v
    file_case[t] = FILENAME
    if ((FILENAME, v) in limit_of)
        limit[t] = limit_of[FILENAME, v]
}
END {
    for (i = 1; i <= count; i++) {
        t = order[i]
        printf "%s\t%s\t%d\t%d\n", t, file_of[t], line_of[t], limit[t] + 0
    }
}
