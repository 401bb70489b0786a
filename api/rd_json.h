/* rd_json — compact JSON text of a jansson value, reals by rd_dtoa, and the
 * reals of results and echoes as jansson values (rd_json.c).
 *
 * rd_json_dumps(v, digits, sort) writes byte for byte what
 *     json_dumps(v, JSON_COMPACT | JSON_REAL_PRECISION(digits) [| JSON_SORT_KEYS])
 * writes, for digits 1..17, at a fraction of the cost: jansson prints each
 * real with the C library's printf and checks every array and object for
 * cycles with a hash table.  digits = 0 writes every real as its shortest
 * round-trip text (rd_dtoa_shortest), where jansson would use 17 digits.
 * Objects keep their insertion order unless `sort` (keys by bytes, as
 * jansson).  A real always holds a '.' or an 'e', so that it reads back as
 * a real.
 *
 * v must be an object or an array nested at most RD_JSON_MAX_DEPTH deep
 * (a cycle exceeds it).  Returns a malloc'd NUL-terminated text the caller
 * frees, or NULL (out of memory, or v not as required). */
#ifndef RD_JSON_H
#define RD_JSON_H

#include <jansson.h>

#define RD_JSON_MAX_DEPTH 2048

char *rd_json_dumps(const json_t *v, int digits, int sort);

/* json_copy (a shallow copy of an object or array), or NULL when memory
 * runs out: jansson's json_copy then returns a copy short of the members
 * or items it had no memory for (found by tests/fuzz's allocation
 * failures). */
json_t *rd_json_copy(json_t *v);

/* A real, or null when it is not finite (NaN: nothing estimated); jansson
 * refuses non-finite reals.  NULL only when out of memory. */
json_t *rd_result_real(double x);

/* [scale * x[0], scale * x[stride], ...], n values; NULL on out of memory. */
json_t *rd_result_reals(const double *x, int n, int stride, double scale);

#endif
