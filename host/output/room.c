/* room.c - room_for_one (room.h). */
#include "room.h"

#include <stdlib.h>

void *room_for_one(void *table, int count, int *cap, size_t size, int first)
{
    if (count < *cap)
        return table;
    int grown_cap = *cap > 0 ? 2 * *cap : first;
    void *grown = realloc(table, (size_t)grown_cap * size);
    if (!grown)
        return NULL;
    *cap = grown_cap;
    return grown;
}
