/* array.h: arrays that grow by doubling, within a limit (chapter 2). */
#ifndef ARRAY_H
#define ARRAY_H

#include <assert.h>
#include "memory.h"

/* The capacity a full array of capacity grows to: twice as much (at least
 * 8), but never more than max. */
static inline int array_next_capacity(int capacity, int max)
{
    int wanted = capacity ? 2 * capacity : 8;
    return wanted < max ? wanted : max;
}

/* Room for needed elements in all: returns items (moved if it had to
 * grow, doubling until there is room), or NULL, leaving items as they
 * were, when needed passes max or memory runs out. */
static inline void *array_reserve(void *items, int needed, int *capacity,
                                  int max, size_t size)
{
    if (needed <= *capacity)
        return items;
    if (needed > max)
        return NULL;
    int wanted = *capacity;
    while (wanted < needed)
        wanted = array_next_capacity(wanted, max);
    void *grown = memory_resize(items, (size_t)wanted, size);
    if (grown != NULL)
        *capacity = wanted;
    return grown;
}

/* Room for one more element after count: array_reserve of count + 1. */
static inline void *array_grow(void *items, int count, int *capacity, int max,
                               size_t size)
{
    assert(0 <= count && count <= *capacity); /* else memory is overrun */
    return array_reserve(items, count + 1, capacity, max, size);
}

#endif
