/* memory.h: every allocation of the program, in one place (chapter 1).
 *
 * Each function returns NULL when count * size overflows or memory runs
 * out, and never for a request of 0 bytes (it asks for 1); what it
 * returns is freed with free(). memory_resize leaves p as it was when it
 * fails. Not for several threads at once: the program allocates on its
 * main thread. */
#ifndef MEMORY_H
#define MEMORY_H

#include <stddef.h>

void *memory_resize(void *p, size_t count, size_t size);
void *memory_alloc(size_t count, size_t size);
void *memory_alloc_zeroed(size_t count, size_t size);
char *memory_copy_string(const char *text);

/* Aligned to alignment, a power of two that is a multiple of
 * sizeof(void *): for data that must start a cache line. */
void *memory_alloc_aligned(size_t alignment, size_t count, size_t size);

/* For tests: from now on the first n allocations succeed and every later
 * one fails; n < 0 lets all succeed again. */
void memory_fail_after(long n);

#endif
