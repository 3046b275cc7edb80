/* check.h - a minimal test harness: CHECK records a pass or a failure with its location and
 * the case CHECK_CASE named last, and check_summary() prints "N passed, M failed" and gives
 * the exit status. */
#ifndef BRDF_TEST_CHECK_H
#define BRDF_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed, check_failed;
/* The case being checked (CHECK_CASE), named in every failure line until the next. */
static const char *check_case_name;
#define CHECK_CASE(name) (check_case_name = (name))

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond) {                                                             \
            ++check_passed;                                                     \
        } else {                                                                \
            ++check_failed;                                                     \
            fprintf(stderr, "FAIL %s:%d: %s%s%s%s: ", __FILE__, __LINE__,       \
                    check_case_name ? "[" : "", check_case_name ? check_case_name : "", \
                    check_case_name ? "] " : "", #cond);                        \
            fprintf(stderr, __VA_ARGS__);                                       \
            fputc('\n', stderr);                                                \
        }                                                                       \
    } while (0)

/* |a - b| <= tol, with both values in the message. */
#define CHECK_NEAR(a, b, tol, what)                                             \
    CHECK(fabs((double)(a) - (double)(b)) <= (tol), "%s: %.17g vs %.17g (tol %g)", \
          (what), (double)(a), (double)(b), (double)(tol))

static inline int check_summary(void)
{
    printf("%d passed, %d failed\n", check_passed, check_failed);
    return check_failed ? 1 : 0;
}

/* The closing line of a test whose device checks could not run (no OpenCL device): 77, the
 * skip code of EXIT_NO_DEVICE and of ctest's SKIP_RETURN_CODE, unless a host check failed,
 * which the skip must not hide (1). */
static inline int check_summary_skipped(void)
{
    check_summary();
    return check_failed ? 1 : 77;
}

#endif
