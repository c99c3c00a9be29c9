/* Minimal test helpers shared by every test executable.
 * A failed CHECK prints file:line and the expression, counts the failure and
 * continues; tests end with `return check_finish();` (0 = pass, 1 = fail).
 * Tests that cannot run (no GL context, no ../shared) return TEST_SKIP,
 * except in CI (CI=true), where both are failures: a CI run must not stay
 * green with the GPU tests or the shared-asset cases silently left out. */
#ifndef DIRT_TEST_CHECK_H
#define DIRT_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define TEST_SKIP 77

/* CI=true (what CI services set): missing prerequisites fail. */
static inline int test_in_ci(void)
{
    const char *ci = getenv("CI");
    return ci && ci[0] == 't' && ci[1] == 'r' && ci[2] == 'u' && ci[3] == 'e' && !ci[4];
}

static int check_failures_;
static int check_count_;

#define CHECK(cond) do { check_count_++; if (!(cond)) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); } } while (0)

#define CHECK_MSG(cond, ...) do { check_count_++; if (!(cond)) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
    fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); } } while (0)

#define CHECK_NEAR(a, b, tol) do { double a_ = (a), b_ = (b); check_count_++; \
    if (!(fabs(a_ - b_) <= (tol))) { check_failures_++; \
    fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %.3g\n", \
            __FILE__, __LINE__, #a, a_, #b, b_, (double)(tol)); } } while (0)

static inline int check_finish(void)
{
    fprintf(stderr, "%d checks, %d failed\n", check_count_, check_failures_);
    return check_failures_ ? 1 : 0;
}

/* Directory of the shared assets (../shared), or NULL when absent; in CI
 * (test_in_ci) an absent directory ends the test as a failure (exit 1). */
static inline const char *test_shared_dir(void)
{
    const char *d = getenv("DIRT_SHARED_DIR");
    FILE *f = NULL;
    char probe[4096];
    if (d && *d) {
        snprintf(probe, sizeof(probe), "%s/scenes/CREDITS.md", d);
        f = fopen(probe, "rb");
    }
    if (!f) {
        if (test_in_ci()) {
            fprintf(stderr, "CI=true: the shared assets are missing (DIRT_SHARED_DIR=%s): "
                            "failing instead of skipping their cases\n", d ? d : "(unset)");
            exit(1);
        }
        return NULL;
    }
    fclose(f);
    return d;
}

#endif
