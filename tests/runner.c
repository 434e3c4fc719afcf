/* runner.c: main() for a test binary made of several Check suites.
 *
 * The Makefile compiles this file with SUITE_LIST defined as a list of
 * X(name) entries, one per suite, e.g. -D'SUITE_LIST=X(ch01_camera)'; each
 * names a function `Suite *name_suite(void)` in tests/name.c. The exit status
 * is 0 only when every test of every suite passed.
 *
 * RUNNER_SHARD=K/N runs only the tests whose number, counted from 0 over
 * every suite in the list's order, leaves K when divided by N (tests/
 * shard.h): N runners, one a shard, run the tests on N cores at once.
 *
 * RUNNER_ONLY="NAME..." runs only the tests of those names, separated by
 * blanks (tools/workbook/grade.sh, to run again the tests that failed with
 * some of the reader's exercises in place of the book's code).
 *
 * RUNNER_THREADED=1 runs only the tests that say they start threads in
 * the test's own process (tcase_add_threaded_test, shard.h): the grader
 * runs them again built with ThreadSanitizer.
 *
 * RUNNER_FORKLESS=1 runs in a process of its own (forked, Check's way)
 * only the tests that expect a signal or an exit status or that say they
 * need one (tcase_add_test_in_a_process, shard.h), first, and every other
 * test one after another in the runner's own process: a sanitized child
 * costs tens of milliseconds to start and to check for leaks at its exit,
 * and the leak check at the runner's exit covers every test all the same.
 * A test that hangs is not stopped then (no child to time out): the
 * unsanitized pass, forked and timed, runs first. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Which of the tests a pass over the suites adds. */
enum adding { EVERY_TEST, TESTS_NEEDING_A_PROCESS, THE_OTHER_TESTS };

static enum adding adding = EVERY_TEST;
static int next_test, next_slow_test; /* counted from 0 for each pass */

/* Whether test number `number` belongs to this runner's shard. */
static int in_shard(int number)
{
    static int k = -1, n = 1;
    if (k < 0) { /* the first test: read the shard, or keep every test */
        const char *shard = getenv("RUNNER_SHARD");
        if (shard == NULL || sscanf(shard, "%d/%d", &k, &n) != 2 || n < 1 ||
            k < 0 || k >= n)
            k = 0, n = 1;
    }
    return number % n == k;
}

static int next_needs_a_process; /* said by the suite for one test */
static int next_is_slow;         /* likewise */
static int next_is_threaded;     /* likewise */

void runner_next_test_needs_a_process(void)
{
    next_needs_a_process = 1;
}

void runner_next_test_is_slow(void)
{
    next_is_slow = 1;
}

void runner_next_test_is_threaded(void)
{
    next_is_threaded = 1;
}

/* Whether name is one of the blank-separated names of list. */
static int is_listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n) {
        int starts = p == list || p[-1] == ' ';
        int ends = p[n] == '\0' || p[n] == ' ';
        if (starts && ends)
            return 1;
    }
    return 0;
}

int runner_keeps_next_test(const char *name, int expected_signal,
                           int expected_exit)
{
    int needs_a_process =
        next_needs_a_process || expected_signal != 0 || expected_exit != 0;
    int slow = next_is_slow, threaded = next_is_threaded;
    next_needs_a_process = next_is_slow = next_is_threaded = 0;
    const char *only = getenv("RUNNER_ONLY");
    if (only != NULL && only[0] != '\0' && !is_listed(only, name))
        return 0;
    const char *threads = getenv("RUNNER_THREADED");
    if (threads != NULL && threads[0] == '1' && !threaded)
        return 0;
    if (!in_shard(slow ? next_slow_test++ : next_test++))
        return 0;
    return adding == EVERY_TEST ||
           needs_a_process == (adding == TESTS_NEEDING_A_PROCESS);
}

#define X(name) Suite *name##_suite(void);
SUITE_LIST
#undef X

/* Runs the tests this pass adds; returns how many failed. */
static int run_pass(enum adding what, enum fork_status fork)
{
    adding = what;
    next_test = next_slow_test = 0;
    SRunner *runner = srunner_create(NULL);
#define X(name) srunner_add_suite(runner, name##_suite());
    SUITE_LIST
#undef X
    if (what != EVERY_TEST)
        srunner_set_fork_status(runner, fork);
    srunner_run_all(runner, CK_ENV); /* CK_VERBOSITY=verbose: every test */
    int failed = srunner_ntests_failed(runner);
    srunner_free(runner);
    return failed;
}

int main(void)
{
    const char *forkless = getenv("RUNNER_FORKLESS");
    int failed;
    if (forkless != NULL && forkless[0] == '1')
        failed = run_pass(TESTS_NEEDING_A_PROCESS, CK_FORK) +
                 run_pass(THE_OTHER_TESTS, CK_NOFORK);
    else
        failed = run_pass(EVERY_TEST, CK_FORK_GETENV);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
