/* pool.c: one pool of threads (chapter 12). See pool.h. */
#include "pool.h"

#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <unistd.h>

/* <<the pool's state>> ch12 */
/* The helpers, and the loop they are called to. Every member but next
 * is read and written with lock held. */
static struct {
    pthread_mutex_t lock;
    pthread_cond_t work;      /* helpers wait here for a seat in a loop */
    pthread_cond_t done;      /* the calling thread, for its helpers */
    int started;              /* helpers: they end with the program */
    bool cannot_start;        /* a start failed: no more are tried */
    void (*job)(void *, int); /* the loop under way */
    void *context;
    int count;
    atomic_int next; /* its next job */
    int seats;       /* helpers it still wants */
    int helping;     /* helpers in it now */
} pool = {.lock = PTHREAD_MUTEX_INITIALIZER,
          .work = PTHREAD_COND_INITIALIZER,
          .done = PTHREAD_COND_INITIALIZER};

/* A loop is under way: another runs on the thread that asks for it. */
static atomic_bool busy;

int pool_threads(int threads)
{
    long n = threads > 0 ? threads : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n < POOL_MAX_THREADS ? (int)n : POOL_MAX_THREADS;
}

/* <<a helper's life>> ch12 */
/* Calls job(context, k) for each k that no other thread has taken, until
 * none is left. */
static void take_jobs(void (*job)(void *, int), void *context, int count)
{
    for (int k; (k = atomic_fetch_add(&pool.next, 1)) < count;)
        job(context, k);
}

/* A helper: wait for a seat in a loop, take its jobs until none is left,
 * leave it; again, until the program ends. */
static void *helper(void *unused)
{
    (void)unused;
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        while (pool.seats == 0)
            pthread_cond_wait(&pool.work, &pool.lock);
        pool.seats--, pool.helping++;
        void (*job)(void *, int) = pool.job;
        void *context = pool.context;
        int count = pool.count;
        pthread_mutex_unlock(&pool.lock);
        take_jobs(job, context, count);
        pthread_mutex_lock(&pool.lock);
        if (--pool.helping == 0)
            pthread_cond_signal(&pool.done); /* the last one out */
    }
    return NULL;
}

/* <<starting a helper>> ch12 */
/* Starts one more helper, holding back every signal but a fault's, so
 * that the signals which stop the program reach the main thread. A
 * helper that cannot start is not tried again. */
static void start_helper(void)
{
    sigset_t held, before;
    sigfillset(&held);
    const int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};
    for (int k = 0; k < 4; k++)
        sigdelset(&held, faults[k]);
    pthread_sigmask(SIG_SETMASK, &held, &before);
    pthread_t id;
    if (pthread_create(&id, NULL, helper, NULL) == 0)
        pool.started++;
    else
        pool.cannot_start = true;
    pthread_sigmask(SIG_SETMASK, &before, NULL);
}

/* <<a loop on the pool>> ch12 */
/* Sets out a loop of count jobs for at most n - 1 helpers, starting the
 * helpers it lacks, and wakes them; how many seats it offered. */
static int offer_seats(int n, void (*job)(void *, int), void *context,
                       int count)
{
    pthread_mutex_lock(&pool.lock);
    while (pool.started < n - 1 && !pool.cannot_start)
        start_helper();
    int helpers = n - 1 < pool.started ? n - 1 : pool.started;
    pool.job = job, pool.context = context, pool.count = count;
    atomic_store(&pool.next, 0);
    pool.seats = helpers;
    for (int k = 0; k < helpers; k++)
        pthread_cond_signal(&pool.work);
    pthread_mutex_unlock(&pool.lock);
    return helpers;
}

/* Once no job is left to take: withdraws the seats not taken, and waits
 * until the helpers in the loop have left it. */
static void wait_for_helpers(void)
{
    pthread_mutex_lock(&pool.lock);
    pool.seats = 0;
    while (pool.helping > 0)
        pthread_cond_wait(&pool.done, &pool.lock);
    pthread_mutex_unlock(&pool.lock);
}

int pool_for(int count, int threads, void (*job)(void *, int),
             void *context)
{
    int n = count > 1 ? pool_threads(threads) : 1; /* asks the system */
    n = n < count ? n : count;
    if (n <= 1 || atomic_exchange(&busy, true)) { /* here, at once */
        for (int k = 0; k < count; k++)
            job(context, k);
        return 1;
    }
    int helpers = offer_seats(n, job, context, count);
    take_jobs(job, context, count); /* this thread is a worker too */
    wait_for_helpers();
    atomic_store(&busy, false);
    return 1 + helpers;
}

int pool_started(void)
{
    pthread_mutex_lock(&pool.lock);
    int n = pool.started;
    pthread_mutex_unlock(&pool.lock);
    return n;
}
