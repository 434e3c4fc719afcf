/* runner.c: main() for a test binary made of several Check suites.
 *
 * The Makefile compiles this file with SUITE_LIST defined as a list of
 * X(name) entries, one per suite, e.g. -D'SUITE_LIST=X(ch01_camera)'; each
 * names a function `Suite *name_suite(void)` in tests/name.c. The exit status
 * is 0 only when every test of every suite passed. */
#include <check.h>
#include <stdlib.h>

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
