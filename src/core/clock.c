#include "dirt/clock.h"
#include "dirt/stats.h"

#include <time.h>

double dirt_clock_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

const char *const dirt_clock_names[3] = {"none", "gpu", "cpu"};
