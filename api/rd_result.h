/*
 * rd_result — what every result writer shares: the CSV
 * table of a result (declared by each analysis as columns of its result
 * object), and the result document (rd_api.h) that writes both the JSON
 * and the CSV from the one object built by the runner.
 *
 * api-internal; jansson values are passed as struct json_t so this header
 * does not pull in jansson.h.
 */
#ifndef RD_RESULT_H
#define RD_RESULT_H

#include <stddef.h>

#include "rd_error.h"

struct json_t;
struct rd_analysis_def;
struct rd_result_doc;

/* Significant digits of the reals in a result: well below the model's
 * discretization error (~1e-3) and the solver tolerance, and it keeps the
 * mode shapes of a large ring (60 modes x 4 x 2000 numbers) compact. */
#define RD_RESULT_REAL_DIGITS 10

/* One CSV column: its header (name with unit), the result key it reads and
 * whether its cells are text (else numbers or null, written %.10g, empty
 * for null).  A key that starts with '/' is a JSON Pointer into the whole
 * result (its first token without ~ escapes) to one value written in every
 * row: a number that holds for the whole table, such as a setting the run
 * used; an empty cell when the result has none. */
typedef struct rd_csv_column {
    const char *header, *key;
    int text; /* 1: cells are text; RD_CSV_OPTIONAL added: a member the result may
               * leave out (the column then too) */
} rd_csv_column;
#define RD_CSV_OPTIONAL 2

/* A result's main table.  Either `rows` names an array of objects (one row
 * each, a column per key), or the columns are equal-length arrays found in
 * the result object, or in its member `object` when that is not NULL. */
typedef struct rd_csv_table {
    const char *object;
    const char *rows;
    const rd_csv_column *columns; /* ended by a NULL header */
} rd_csv_table;

/* The table of `result` (borrowed) as CSV text, malloc'd: a header row, one
 * row per entry.  A result that does not have the table's shape is
 * RD_EINTERNAL ("malformed <analysis> result: ..."). */
char *rd_result_csv(struct json_t *result, const rd_csv_table *table, const char *analysis,
                    rd_error *err);

/* A result document (rd_api.h) of analysis `an` holding `result`, which it
 * takes over; NULL when out of memory (then `result` stays the caller's). */
struct rd_result_doc *rd_result_doc_new(const struct rd_analysis_def *an, struct json_t *result);

#endif
