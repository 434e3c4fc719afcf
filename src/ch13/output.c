/* output.c: the output file and the signals that may stop its writing
 * (chapter 1). */
#include "output.h"

#include <signal.h>
#include <string.h>
#include <unistd.h>
#include "parse.h"

/* <<the output file>> ch01 */
/* The output's temporary file, while there is one. */
static char temporary[PARSE_MAX_NAME + 16];
static volatile sig_atomic_t has_temporary;

static void remove_temporary_and_stop(int sig)
{
    if (has_temporary)
        unlink(temporary);
    raise(sig); /* SA_RESETHAND restored the default action: it stops */
}

/* Every signal whose default action ends the program and that comes from
 * outside it: the user, the system, a timer, a limit. */
static const int stop_signals[] = {SIGINT,  SIGTERM,   SIGHUP,  SIGQUIT,
                                   SIGALRM, SIGUSR1,   SIGUSR2, SIGXCPU,
                                   SIGVTALRM, SIGPROF};
enum { STOP_SIGNALS = sizeof stop_signals / sizeof stop_signals[0] };

void output_catch_stop_signals(void)
{
    struct sigaction action = {.sa_handler = remove_temporary_and_stop,
                               .sa_flags = SA_RESETHAND},
                     before, ignore = {.sa_handler = SIG_IGN};
    sigemptyset(&action.sa_mask), sigemptyset(&ignore.sa_mask);
    for (int k = 0; k < STOP_SIGNALS; k++)
        if (sigaction(stop_signals[k], NULL, &before) == 0 &&
            before.sa_handler != SIG_IGN) /* nohup's choice stands */
            sigaction(stop_signals[k], &action, NULL);
    sigaction(SIGPIPE, &ignore, NULL); /* write fails with EPIPE */
    sigaction(SIGXFSZ, &ignore, NULL); /* write fails with EFBIG */
}

/* The stop signals are held while the file opens, so that the handler
 * knows of a temporary file as soon as it exists. */
bool output_open(const char *path, png_output *out, char *why,
                 size_t why_size)
{
    sigset_t stops, before;
    sigemptyset(&stops);
    for (int k = 0; k < STOP_SIGNALS; k++)
        sigaddset(&stops, stop_signals[k]);
    sigprocmask(SIG_BLOCK, &stops, &before);
    bool ok = png_output_open(out, path, why, why_size);
    if (out->temporary && strlen(out->temporary) < sizeof temporary) {
        strcpy(temporary, out->temporary);
        has_temporary = 1;
    }
    sigprocmask(SIG_SETMASK, &before, NULL);
    return ok;
}

void output_close(png_output *out)
{
    png_output_free(out);
    has_temporary = 0;
}
