/* memory.c: every allocation of the program, in one place (chapter 1). */
#include "memory.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static long allocations_left = -1; /* < 0: no limit */

/* May one more allocation of count * size bytes be made? */
static bool may_allocate(size_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return false; /* the product would overflow */
    if (allocations_left == 0)
        return false;
    if (allocations_left > 0)
        allocations_left--;
    return true;
}

void *memory_resize(void *p, size_t count, size_t size)
{
    if (!may_allocate(count, size))
        return NULL;
    size_t bytes = count * size;
    return realloc(p, bytes > 0 ? bytes : 1);
}

void *memory_alloc(size_t count, size_t size)
{
    return memory_resize(NULL, count, size);
}

void *memory_alloc_zeroed(size_t count, size_t size)
{
    if (!may_allocate(count, size))
        return NULL;
    return count > 0 && size > 0 ? calloc(count, size) : calloc(1, 1);
}

void *memory_alloc_aligned(size_t alignment, size_t count, size_t size)
{
    if (!may_allocate(count, size))
        return NULL;
    size_t bytes = count * size > 0 ? count * size : 1;
    if (bytes > SIZE_MAX - alignment)
        return NULL; /* no room to round it up */
    bytes = (bytes + alignment - 1) / alignment * alignment; /* C11 asks */
    return aligned_alloc(alignment, bytes);
}

char *memory_copy_string(const char *text)
{
    size_t n = strlen(text) + 1;
    char *copy = memory_alloc(n, 1);
    return copy != NULL ? memcpy(copy, text, n) : NULL;
}

void memory_fail_after(long n)
{
    allocations_left = n;
}
