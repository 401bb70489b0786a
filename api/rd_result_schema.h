/*
 * rd_result_schema — result pointers checked against the analysis' result
 * schema in the OpenAPI document (rd_openapi_doc.h), before anything runs:
 * a sweep's outputs, a calibration's observed values, a sensitivity's
 * outputs.  A misspelt member is refused naming it and what exists there
 * (with the closest name), instead of a table of empty cells.
 *
 * The walk follows the pointer through "<Analysis>Result" (Modal, Lift,
 * Ringpack, ...): $ref, allOf (the members' properties together), oneOf /
 * anyOf (the first branch that has the token), objects (a token must be a
 * property; objects that list properties are closed, as the contract tests
 * read them, unless additionalProperties is a schema), arrays (a token must
 * be an index, or the aggregates' * for every element).  A schema the
 * template does not hold (the scene schemas, written when the document is
 * served) or one without properties ends the check there: the rest of the
 * pointer is accepted.
 *
 * Usage:
 *     if (rd_result_pointer_check("ringpack", "/blowby/l_per_min", "/outputs/0", err))
 *         return err->code;   RD_EREQUEST, the path and the reason
 */
#ifndef RD_RESULT_SCHEMA_H
#define RD_RESULT_SCHEMA_H

#include "rd_error.h"

/* RD_OK when ptr can name a value of an `analysis` result (or its schema is
 * unknown), else RD_EREQUEST at `path`; RD_ENOMEM. */
int rd_result_pointer_check(const char *analysis, const char *ptr, const char *path, rd_error *err);

#endif
