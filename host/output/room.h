/* room.h - room for one more item in a malloc'd growable array counted by an int: the one place
 * its doubling is written (the shader translator's arrays live in its arena and grow there). */
#ifndef BRDF_ROOM_H
#define BRDF_ROOM_H

#include <stddef.h>

/* The array `table` of `count` items of `size` bytes, with room for one more: table itself
 * when count < *cap, else the array reallocated to twice *cap (first: the capacity of an empty
 * one) with *cap updated. NULL when memory is out (table and *cap are then unchanged, and the
 * caller still owns table). */
void *room_for_one(void *table, int count, int *cap, size_t size, int first);

#endif
