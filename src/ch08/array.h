/* array.h: arrays that grow by doubling, within a limit (chapter 2). */
#ifndef ARRAY_H
#define ARRAY_H

#include <assert.h>
#include <stdlib.h>

/* The capacity a full array of capacity grows to: twice as much (at least
 * 8), but never more than max. */
static inline int array_next_capacity(int capacity, int max)
{
    int wanted = capacity ? 2 * capacity : 8;
    return wanted < max ? wanted : max;
}

/* Room for one more element: returns items (moved if it had to grow), or
 * NULL, leaving items as they were, at max or when memory runs out. */
static inline void *array_grow(void *items, int count, int *capacity, int max,
                               size_t size)
{
    assert(0 <= count && count <= *capacity); /* else memory is overrun */
    if (count < *capacity)
        return items;
    if (*capacity >= max)
        return NULL;
    int wanted = array_next_capacity(*capacity, max);
    void *grown = realloc(items, (size_t)wanted * size);
    if (grown != NULL)
        *capacity = wanted;
    return grown;
}

#endif
