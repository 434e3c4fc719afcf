/* pool.h: one pool of threads for the whole program (chapter 12).
 *
 * pool_for(count, threads, job, context) calls job(context, k) once for
 * every k in [0, count), on at most threads threads (0: one per core) and
 * never on more threads than jobs, the calling thread among them, and
 * returns when every call has returned. Each thread takes the next k
 * left, so that a long job holds up its own thread only.
 *
 * The pool's helpers are started when a loop first needs them and wait
 * for the next loop after it: a program that asks for at most n threads
 * starts at most n - 1 of them. A loop asked for while another is under
 * way (from inside a job) runs on the thread that asks; when no thread
 * can start, the calling thread does every job itself. */
#ifndef POOL_H
#define POOL_H

/* --threads' largest: threads beyond the cores only wait their turn. */
#define POOL_MAX_THREADS 256

/* The threads that threads asks for: itself, or for 0 one per core; from
 * 1 to POOL_MAX_THREADS. */
int pool_threads(int threads);

/* Runs job(context, k) for every k in [0, count), as said above; how many
 * threads the loop was shared among (1: the calling thread alone). */
int pool_for(int count, int threads, void (*job)(void *context, int k),
             void *context);

/* How many helpers the pool has started since the program began. */
int pool_started(void);

#endif
