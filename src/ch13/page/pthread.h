/* pthread.h for the page (chapter 13): one thread. No thread starts,
 * and the caller does the work it would have shared. */
#ifndef PAGE_PTHREAD_H
#define PAGE_PTHREAD_H

#include <errno.h>
#include <sys/types.h> /* pthread_t and the others, which WASI names */
#include <time.h>

static inline int pthread_create(pthread_t *id, const pthread_attr_t *a,
                                 void *(*run)(void *), void *arg)
{
    (void)id, (void)a, (void)run, (void)arg;
    return EAGAIN; /* as when a system has no thread to spare */
}

static inline int pthread_join(pthread_t id, void **result)
{
    (void)id, (void)result;
    return ESRCH; /* never called: no thread started */
}

/* <<one thread's locks>> ch13 */
/* One thread: every lock is free, and no one waits on a condition. */
static inline int pthread_mutex_init(pthread_mutex_t *m, const void *a)
{
    return (void)m, (void)a, 0;
}
static inline int pthread_mutex_lock(pthread_mutex_t *m) { return (void)m, 0; }
static inline int pthread_mutex_unlock(pthread_mutex_t *m)
{
    return (void)m, 0;
}
static inline int pthread_mutex_destroy(pthread_mutex_t *m)
{
    return (void)m, 0;
}
static inline int pthread_cond_init(pthread_cond_t *c, const void *a)
{
    return (void)c, (void)a, 0;
}
static inline int pthread_condattr_init(pthread_condattr_t *a)
{
    return (void)a, 0;
}
static inline int pthread_condattr_setclock(pthread_condattr_t *a,
                                            clockid_t clock)
{
    return (void)a, (void)clock, 0;
}
static inline int pthread_condattr_destroy(pthread_condattr_t *a)
{
    return (void)a, 0;
}
static inline int pthread_cond_signal(pthread_cond_t *c) { return (void)c, 0; }
static inline int pthread_cond_destroy(pthread_cond_t *c) { return (void)c, 0; }
static inline int pthread_cond_timedwait(pthread_cond_t *c,
                                         pthread_mutex_t *m,
                                         const struct timespec *until)
{
    return (void)c, (void)m, (void)until, 0;
}
static inline int pthread_cond_wait(pthread_cond_t *c, pthread_mutex_t *m)
{
    return (void)c, (void)m, 0;
}
#define PTHREAD_MUTEX_INITIALIZER {{{0}}}
#define PTHREAD_COND_INITIALIZER {{{0}}}

#endif
