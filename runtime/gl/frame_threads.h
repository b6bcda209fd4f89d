/* frame_threads.h — the CPU work of a frame that grows with the patch
 * count (the pass over the hulls, the candidate lists' build), split into
 * shares that run at once on threads of their own. */
#ifndef SC_FRAME_THREADS_H
#define SC_FRAME_THREADS_H

#include <stddef.h>

/* The most threads a frame's work runs on. */
#define SC_FRAME_MAX_THREADS 8

/* Shares for work over `items` items: `wanted` (0: one per online
 * processor), at most SC_FRAME_MAX_THREADS, and at least min_share items
 * each; 1 at least. */
int sc_frame_shares(int wanted, long items, long min_share);

/* Runs fn on each of the n shares (an array of elements `size` bytes
 * long): share 0 on the calling thread, the others on threads of their
 * own, or on the calling thread after share 0 where one cannot start. */
void sc_run_shares(void *(*fn)(void *), void *shares, size_t size, int n);

#endif
