/* frame_threads.c — shares of a frame's CPU work on threads (frame_threads.h).
 * A thread is started per share and joined at once: a frame has two such
 * steps, and starting a thread costs microseconds against the
 * milliseconds of a share. */
#include "frame_threads.h"

#include <pthread.h>
#include <unistd.h>

int sc_frame_shares(int wanted, long items, long min_share)
{
    long n = wanted > 0 ? wanted : sysconf(_SC_NPROCESSORS_ONLN);
    long most = items / min_share;
    n = n < most ? n : most;
    n = n < SC_FRAME_MAX_THREADS ? n : SC_FRAME_MAX_THREADS;
    return n > 1 ? (int)n : 1;
}

void sc_run_shares(void *(*fn)(void *), void *shares, size_t size, int n)
{
    pthread_t ids[SC_FRAME_MAX_THREADS];
    int started[SC_FRAME_MAX_THREADS] = {0};
    char *share = shares;
    for (int t = 1; t < n; t++)
        started[t] = pthread_create(&ids[t], NULL, fn, share + t * size) == 0;
    fn(share);
    for (int t = 1; t < n; t++) {
        if (started[t])
            pthread_join(ids[t], NULL);
        else
            fn(share + t * size);
    }
}
