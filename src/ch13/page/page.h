/* page.h: what the page build reads before every file (chapter 13).
 * The page writes no files: the calls that make, protect and name an
 * output file fail with ENOTSUP, as on a system without them. */
#ifndef PAGE_H
#define PAGE_H

#include <errno.h>
#include <sys/types.h>

static inline int mkstemp(char *name)
{
    (void)name;
    return errno = ENOTSUP, -1;
}

static inline int fchmod(int fd, mode_t mode)
{
    (void)fd, (void)mode;
    return errno = ENOTSUP, -1;
}

static inline mode_t umask(mode_t mask)
{
    return mask; /* no files, so no mode to mask */
}

static inline char *realpath(const char *path, char *resolved)
{
    (void)path, (void)resolved;
    return errno = ENOTSUP, NULL;
}

#endif
