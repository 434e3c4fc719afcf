/* runner.c: main() for a test binary made of several Check suites.
 *
 * The Makefile compiles this file with SUITE_LIST defined as a list of
 * X(name) entries, one per suite, e.g. -D'SUITE_LIST=X(ch01_camera)'; each
 * names a function `Suite *name_suite(void)` in tests/name.c. The exit status
 * is 0 only when every test of every suite passed.
 *
 * RUNNER_SHARD=K/N runs only the suites whose place in the list, counted
 * from 0, leaves K when divided by N: N runners, one a shard, run the
 * suites on N cores at once. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>

/* Whether suite number index belongs to this runner's shard. */
static int in_shard(int index)
{
    const char *shard = getenv("RUNNER_SHARD");
    int k, n;
    if (shard == NULL || sscanf(shard, "%d/%d", &k, &n) != 2 || n < 1)
        return 1; /* no shard, or a malformed one: every suite */
    return index % n == k;
}

#define X(name) Suite *name##_suite(void);
SUITE_LIST
#undef X

int main(void)
{
    SRunner *runner = srunner_create(NULL);
    int index = 0;
#define X(name)                                                              \
    if (in_shard(index++))                                                   \
        srunner_add_suite(runner, name##_suite());
    SUITE_LIST
#undef X
    srunner_run_all(runner, CK_ENV); /* CK_VERBOSITY=verbose: every test */
    int failed = srunner_ntests_failed(runner);
    srunner_free(runner);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
