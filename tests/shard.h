/* shard.h: a test runner's share of the tests (tests/runner.c).
 *
 * With RUNNER_SHARD=K/N a runner keeps only the tests whose number,
 * counted from 0 over every suite in the runner's order, leaves K when
 * divided by N: N runners, one a shard, run the tests on N cores at once,
 * and the slow tests of one suite are spread among them; the tests said
 * to be slow (tcase_add_slow_test) are counted and dealt on their own.
 * Check adds every kind of test through _tcase_add_test, so the suites
 * need no change: the macro asks the runner before each one (in its own
 * expansion the name is Check's function again), and tells it whether the
 * test expects a signal or an exit status, which only a process of its
 * own can give. */
#ifndef SHARD_H
#define SHARD_H

#include <check.h>

/* Whether the next test added, named name, belongs to this runner's
 * share (with RUNNER_ONLY="NAME...", only the tests of those names do;
 * with RUNNER_THREADED=1, only those added as threaded). */
int runner_keeps_next_test(const char *name, int expected_signal,
                           int expected_exit);

/* Says that the next test added needs a process of its own all the same. */
void runner_next_test_needs_a_process(void);

/* Says that the next test added is slow (a second or more, or waits):
 * the slow tests are dealt out among the shards apart from the others,
 * so that no shard gets two of them while another gets none. */
void runner_next_test_is_slow(void);

/* Says that the next test added starts threads in its own process: the
 * grader runs such tests again built with ThreadSanitizer, which sees a
 * data race whether or not it changed the result this time. */
void runner_next_test_is_threaded(void);

#define tcase_add_threaded_test(tc, tf)                                      \
    (runner_next_test_is_threaded(), tcase_add_test(tc, tf))

#define tcase_add_slow_test(tc, tf)                                          \
    (runner_next_test_is_slow(), tcase_add_test(tc, tf))

/* A test that measures a program it starts by the program's peak memory:
 * Linux counts in a child's peak the memory of the process it was forked
 * from, which a runner that runs every test itself grows with each one. */
#define tcase_add_test_in_a_process(tc, tf)                                  \
    (runner_next_test_needs_a_process(), tcase_add_test(tc, tf))

#define _tcase_add_test(tc, tt, sig, exit_value, start, end)                 \
    (runner_keeps_next_test((tt)->name, (sig), (exit_value))                 \
         ? _tcase_add_test(tc, tt, sig, exit_value, start, end)              \
         : (void)0)

#endif
