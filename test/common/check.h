/* Minimal test helpers shared by every test executable.
 * A failed CHECK prints file:line and the expression, counts the failure and
 * continues; tests end with `return check_finish();` (0 = pass, 1 = fail).
 * Tests that cannot run (no GL context, no ../shared) return TEST_SKIP. */
#ifndef DIRT_TEST_CHECK_H
#define DIRT_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define TEST_SKIP 77

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

/* Directory of the shared assets (../shared), or NULL when absent. */
static inline const char *test_shared_dir(void)
{
    const char *d = getenv("DIRT_SHARED_DIR");
    if (!d || !*d)
        return NULL;
    FILE *f;
    char probe[4096];
    snprintf(probe, sizeof(probe), "%s/scenes/CREDITS.md", d);
    f = fopen(probe, "rb");
    if (!f)
        return NULL;
    fclose(f);
    return d;
}

#endif
