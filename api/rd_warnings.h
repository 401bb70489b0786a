/*
 * rd_warnings — the "warnings" of a result (rd_warnings.c holds the rules
 * as a table, with their thresholds and reasons).  api-internal.
 */
#ifndef RD_WARNINGS_H
#define RD_WARNINGS_H

struct json_t;

/* Sets result["warnings"] to the list of {code, path, message} the rules
 * find in the finished result object (its "scene" echo and "numerics");
 * an empty list when none.  0, or -1 on out of memory. */
int rd_warnings_add(struct json_t *result);

#endif
