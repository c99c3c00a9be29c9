/* DIRT engine, src/ref: a minimal parallel-for on pthreads. */
#ifndef DIRT_REF_PARALLEL_H
#define DIRT_REF_PARALLEL_H

#include <stddef.h>

/* Work item callback: process items [begin, end) on worker `worker`
 * (0 <= worker < the thread count that ref_parallel_for returned). */
typedef void (*ref_range_fn)(void *ctx, size_t begin, size_t end, int worker);

/* Number of online CPUs (at least 1). */
int ref_cpu_count(void);

/* Threads a request for `threads` gets: threads > 0 as asked, 0 = every
 * online CPU. */
int ref_thread_count(int threads);

/* Runs fn over [0, count) in chunks of `chunk` items handed out dynamically
 * to `threads` workers (the calling thread is worker 0). If a thread cannot
 * be started, the remaining workers (at least the caller) do its share.
 * Returns the number of workers that ran. */
int ref_parallel_for(size_t count, size_t chunk, int threads, ref_range_fn fn,
                     void *ctx);

#endif
