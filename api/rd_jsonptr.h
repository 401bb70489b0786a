/*
 * rd_jsonptr — JSON Pointers (RFC 6901) over jansson values, for the sweep
 * module: read a value, write one (creating missing objects on the way), and
 * collect the values a pointer with `*` wildcards names.
 *
 * A pointer is "" (the whole document) or a sequence of "/token"; in a token
 * "~1" stands for '/' and "~0" for '~' (decoded in that order, as the RFC
 * says), and any other '~' makes the pointer malformed.  An array is indexed
 * by a decimal token without leading zeros ("0", "12", not "012", "-1").
 * api-internal: the public face is rd_sweep.h.
 */
#ifndef RD_JSONPTR_H
#define RD_JSONPTR_H

#include <jansson.h>

/* 1 if `ptr` is a well-formed pointer ("" or "/..." with only ~0/~1 escapes). */
int rd_jsonptr_valid(const char *ptr);

/* The value `ptr` names in `root` (borrowed), or NULL if there is none or
 * `ptr` is malformed.  A "*" token is an ordinary key here. */
json_t *rd_jsonptr_get(json_t *root, const char *ptr);

/* rd_jsonptr_get that tells why nothing was found: 0 (*out is the value),
 * -1 no such value or `ptr` malformed, -2 out of memory. */
int rd_jsonptr_lookup(json_t *root, const char *ptr, json_t **out);

/* Sets the value `ptr` names in `root` to `value` (the reference is stolen,
 * also on failure).  Missing object members on the way are created as empty
 * objects; an array element must exist, or the token is the array's length
 * (append).  Returns 0; -1 when `ptr` is "" or malformed, crosses a scalar or
 * indexes an array out of range; -2 when memory runs out (or `value` is NULL). */
int rd_jsonptr_set(json_t *root, const char *ptr, json_t *value);

/* Appends to `out` (a JSON array) every value `ptr` names in `root`, where a
 * "*" token stands for every element of an array or every member of an
 * object (in order; members in jansson's iteration order).  Paths that do not
 * exist add nothing.  Returns 0, or -1 when `ptr` is malformed or memory runs
 * out. */
int rd_jsonptr_collect(json_t *root, const char *ptr, json_t *out);

#endif
