/* shard.h: a test runner's share of the tests (tests/runner.c).
 *
 * With RUNNER_SHARD=K/N a runner keeps only the tests whose number,
 * counted from 0 over every suite in the runner's order, leaves K when
 * divided by N: N runners, one a shard, run the tests on N cores at once,
 * and the slow tests of one suite are spread among them. Check adds every
 * kind of test through _tcase_add_test, so the suites need no change: the
 * macro asks the runner before each one (in its own expansion the name is
 * Check's function again). */
#ifndef SHARD_H
#define SHARD_H

#include <check.h>

/* Whether the next test added belongs to this runner's shard. */
int runner_keeps_next_test(void);

#define _tcase_add_test(...)                                                 \
    (runner_keeps_next_test() ? _tcase_add_test(__VA_ARGS__) : (void)0)

#endif
