/* signal.h for the page (chapter 13): no signal is ever delivered. */
#ifndef PAGE_SIGNAL_H
#define PAGE_SIGNAL_H

typedef int sig_atomic_t;
typedef unsigned sigset_t;
struct sigaction {
    void (*sa_handler)(int);
    sigset_t sa_mask;
    int sa_flags;
};
enum { SIGHUP = 1, SIGINT = 2, SIGQUIT = 3, SIGUSR1 = 10, SIGUSR2 = 12,
       SIGPIPE = 13, SIGALRM = 14, SIGTERM = 15, SIGXCPU = 24,
       SIGXFSZ = 25, SIGVTALRM = 26, SIGPROF = 27 }; /* Linux's numbers */
enum { SIGILL = 4, SIGBUS = 7, SIGFPE = 8, SIGSEGV = 11 }; /* faults */
enum { SA_RESETHAND = 1, SIG_BLOCK = 0, SIG_SETMASK = 2 };
#define SIG_IGN ((void (*)(int))1)

static inline int sigemptyset(sigset_t *s) { return *s = 0, 0; }
static inline int sigfillset(sigset_t *s) { return *s = ~0u, 0; }
static inline int sigaddset(sigset_t *s, int sig)
{
    return *s |= 1u << sig, 0;
}
static inline int sigprocmask(int how, const sigset_t *s, sigset_t *was)
{
    (void)how, (void)s;
    return was != NULL ? *was = 0, 0 : 0;
}
static inline int sigdelset(sigset_t *s, int sig)
{
    return *s &= ~(1u << sig), 0;
}
static inline int pthread_sigmask(int how, const sigset_t *s, sigset_t *was)
{
    return sigprocmask(how, s, was);
}
/* Every signal is ignored already: output.c then leaves it so. */
static inline int sigaction(int sig, const struct sigaction *a,
                            struct sigaction *was)
{
    (void)sig, (void)a;
    return was != NULL ? was->sa_handler = SIG_IGN, 0 : 0;
}
static inline int raise(int sig) { return (void)sig, 0; }

#endif
