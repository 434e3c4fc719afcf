/* runner.c: main() for a test binary made of several Check suites.
 *
 * The Makefile compiles this file with SUITE_LIST defined as a list of
 * X(name) entries, one per suite, e.g. -D'SUITE_LIST=X(ch01_camera)'; each
 * names a function `Suite *name_suite(void)` in tests/name.c. The exit status
 * is 0 only when every test of every suite passed.
 *
 * RUNNER_SHARD=K/N runs only the tests whose number, counted from 0 over
 * every suite in the list's order, leaves K when divided by N (tests/
 * shard.h): N runners, one a shard, run the tests on N cores at once. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>

/* Whether the next test added belongs to this runner's shard. */
int runner_keeps_next_test(void)
{
    static int next = 0, k = -1, n = 1;
    if (k < 0) { /* the first test: read the shard, or keep every test */
        const char *shard = getenv("RUNNER_SHARD");
        if (shard == NULL || sscanf(shard, "%d/%d", &k, &n) != 2 || n < 1 ||
            k < 0 || k >= n)
            k = 0, n = 1;
    }
    return next++ % n == k;
}

#define X(name) Suite *name##_suite(void);
SUITE_LIST
#undef X

int main(void)
{
    SRunner *runner = srunner_create(NULL);
#define X(name) srunner_add_suite(runner, name##_suite());
    SUITE_LIST
#undef X
    srunner_run_all(runner, CK_ENV); /* CK_VERBOSITY=verbose: every test */
    int failed = srunner_ntests_failed(runner);
    srunner_free(runner);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
