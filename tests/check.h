/* The tests' one family of checks: a failed check prints where and what (file:line, the condition, a message) on
 * stderr and counts; the test keeps going so that one run shows every failure, and check_report() gives the exit
 * status. Header-only, one copy per test executable. */
#ifndef VKSKY_TESTS_CHECK_H
#define VKSKY_TESTS_CHECK_H
#include <math.h>
#include <stdio.h>

static int check_failures, check_count;

#define CHECK(cond, ...)                                                                                    \
    do {                                                                                                    \
        ++check_count;                                                                                      \
        if (!(cond)) {                                                                                      \
            ++check_failures;                                                                               \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                 \
            fprintf(stderr, __VA_ARGS__);                                                                   \
            fputc('\n', stderr);                                                                            \
        }                                                                                                   \
    } while (0)

/* |a - b| < tol (NaN fails), with both values in the message. */
#define CHECK_NEAR(a, b, tol, what)                                                                         \
    do {                                                                                                    \
        double check_a_ = (double)(a), check_b_ = (double)(b);                                              \
        ++check_count;                                                                                      \
        if (!(fabs(check_a_ - check_b_) < (double)(tol))) {                                                 \
            ++check_failures;                                                                               \
            fprintf(stderr, "FAIL %s:%d: %s = %.9g vs %s = %.9g (tolerance %g): %s\n", __FILE__, __LINE__,  \
                    #a, check_a_, #b, check_b_, (double)(tol), what);                                       \
        }                                                                                                   \
    } while (0)

/* The end of a test: a summary line and the exit status (0 when every check held). */
static inline int check_report(const char *name)
{
    if (check_failures) fprintf(stderr, "%s: %d of %d checks failed\n", name, check_failures, check_count);
    else printf("%s: %d checks ok\n", name, check_count);
    return check_failures ? 1 : 0;
}
#endif
