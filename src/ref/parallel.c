/* DIRT engine, src/ref: a minimal parallel-for on pthreads. */
#include "ref/parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

#include "dirt/log.h"

#define MAX_THREADS 256

typedef struct job {
    size_t count, chunk;
    atomic_size_t next;
    ref_range_fn fn;
    void *ctx;
} job;

typedef struct worker_arg {
    job *job;
    int index;
} worker_arg;

int ref_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1)
        return 1;
    return n > MAX_THREADS ? MAX_THREADS : (int)n;
}

int ref_thread_count(int threads)
{
    if (threads <= 0)
        return ref_cpu_count();
    return threads > MAX_THREADS ? MAX_THREADS : threads;
}

static void run_worker(job *j, int index)
{
    for (;;) {
        size_t begin = atomic_fetch_add(&j->next, j->chunk);
        if (begin >= j->count)
            break;
        size_t end = begin + j->chunk < j->count ? begin + j->chunk : j->count;
        j->fn(j->ctx, begin, end, index);
    }
}

static void *thread_main(void *p)
{
    worker_arg *a = p;
    run_worker(a->job, a->index);
    return NULL;
}

int ref_parallel_for(size_t count, size_t chunk, int threads, ref_range_fn fn,
                     void *ctx)
{
    job j;
    j.count = count;
    j.chunk = chunk ? chunk : 1;
    atomic_init(&j.next, 0);
    j.fn = fn;
    j.ctx = ctx;
    int n = ref_thread_count(threads);
    size_t chunks = (count + j.chunk - 1) / j.chunk;
    if ((size_t)n > chunks)
        n = chunks > 0 ? (int)chunks : 1;

    pthread_t tid[MAX_THREADS];
    worker_arg args[MAX_THREADS];
    int started = 0;
    for (int i = 1; i < n; i++) {
        args[started + 1].job = &j;
        args[started + 1].index = started + 1;
        if (pthread_create(&tid[started], NULL, thread_main, &args[started + 1]) != 0) {
            DIRT_WARN("could not start worker thread %d of %d; continuing with fewer", i, n);
            break;
        }
        started++;
    }
    run_worker(&j, 0);
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    return started + 1;
}
