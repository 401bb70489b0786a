/*
 * rd_schema — the scene schema as data, and the one engine that reads it.
 *
 * A scene is described by blocks (JSON objects) of fields.  Each field says
 * its key, JSON type, where its value lives (an offset into struct rd_scene,
 * or into the analysis' own options when its block says so), its static
 * range, its description, and (for the few whose echo is a computed value)
 * how it is echoed.  From the same tables this engine
 *   - parses a JSON block into the scene (type checks, unknown keys),
 *   - writes the echo of a parsed scene (every default filled in),
 *   - writes the OpenAPI schema of the block (types, defaults read from a
 *     defaults-filled scene, ranges, enums, descriptions),
 * so none of the three can drift from the others (rd_schema.c parses,
 * rd_schema_write.c writes the echo and the OpenAPI schema).
 *
 * Ranges: core's validators (the core *_validate functions) stay the authority for value
 * checks and their messages.  A field's min/max here is the static part of
 * the range core enforces (ranges that depend on other fields are said in
 * the description); tests/api/test_schema.c probes every edge through
 * rd_scene_parse, so the table and core cannot disagree unnoticed.
 *
 * Adding a field to an analysis is one line in its block table.
 */
#ifndef RD_SCHEMA_H
#define RD_SCHEMA_H

#include <stddef.h>

#include "rd_error.h"

struct json_t;
struct rd_scene;

enum rd_field_type {
    RD_F_ANALYSIS,   /* "analysis": checked first, on its own; echoed (and its
                        OpenAPI enum written) by the field's `echo` hook */
    RD_F_NUMBER,     /* double, any JSON number */
    RD_F_INTEGER,    /* int: a JSON integer, or a real with an integral value */
    RD_F_BOOL,       /* int 0/1 from JSON true/false only */
    RD_F_STRING,     /* char *, strdup'd; optional metadata, no default */
    RD_F_CHOICE,     /* int: index of the JSON string in `choices` */
    RD_F_BLOCK,      /* nested object with its own block */
    RD_F_OPTBLOCK,   /* RD_F_BLOCK whose presence sets the int at `offset` to 1 */
    RD_F_TABLE,      /* struct rd_table: an array of numbers, malloc'd;
                        min/max count its items */
    RD_F_DISTORTION, /* rd_bore at `offset`: an array of `block` items
                        ({order, amplitude, phase_deg}); max counts the items */
    RD_F_ITEMS,      /* an array of `block` objects read by the field's `parse`
                        hook and echoed by its `echo` (items whose blocks nest
                        shared ones, as the ring pack's rings); min/max count
                        the items; OpenAPI: items = `block` */
    RD_F_CUSTOM      /* a value of any JSON type (a number or "all", a string
                        or an object, an array of `block` items) read by the
                        field's `parse` hook and echoed by its `echo`, which
                        returns JSON null when the field is not echoed (not
                        given); OpenAPI: the JSON schema `extra`, or an array
                        of `block` items (min/max count them) */
};

/* How a bound is meant: none, inclusive, exclusive. */
enum { RD_BOUND_NONE = 0, RD_BOUND_IN = 1, RD_BOUND_EX = 2 };

typedef struct rd_field {
    const char *key;
    enum rd_field_type type;
    size_t offset;                  /* into the block's base (see rd_block.in_opts) */
    const struct rd_block *block;   /* RD_F_BLOCK, RD_F_OPTBLOCK, RD_F_DISTORTION */
    const char *const *choices;     /* RD_F_CHOICE: allowed strings, NULL-ended */
    double min, max;                /* the static range core enforces */
    unsigned char has_min, has_max; /* RD_BOUND_* */
    unsigned char required;         /* the block needs it (no default) */
    unsigned char only_false;       /* RD_F_BOOL that this analysis only allows false */
    unsigned char in_opts;          /* the offset is into the analysis' opts although the
                                      block's are not (a top-level option) */
    unsigned char in_scene;         /* the offset is into the scene although the block's are
                                      into the opts (a shared block's given flag) */
    unsigned char nullable;         /* JSON null is accepted (and may be echoed): the
                                      block's parse hook gives it the meaning its
                                      description says; OpenAPI: nullable, null in the enum */
    const char *desc;               /* the OpenAPI description */
    const char *word;               /* RD_F_NUMBER: this string is also accepted, stored (and
                                      echoed back) as 0, e.g. "periodic" */
    const char *extra;              /* RD_F_BLOCK: JSON schema combined with the block's
                                      (allOf), for what this analysis adds to a shared one */
    /* The echoed value when it is not the stored one (a 0 meaning "the
     * default computed from the ring", echoed as the value used; the
     * analysis' name); a new reference, NULL on out of memory. */
    struct json_t *(*echo)(const struct rd_scene *s);
    /* RD_F_ITEMS: parses the array `v` at `path` into the scene. */
    int (*parse)(const struct rd_field *f, struct json_t *v, const char *path, struct rd_scene *s,
                 rd_error *err);
} rd_field;

/* Bounds, for the tables: {"key", RD_F_NUMBER, AT(x), RD_MIN(0.001), RD_MAX(5.0), ...}. */
#define RD_MIN(x)  .min = (x), .has_min = RD_BOUND_IN
#define RD_XMIN(x) .min = (x), .has_min = RD_BOUND_EX
#define RD_MAX(x)  .max = (x), .has_max = RD_BOUND_IN
#define RD_XMAX(x) .max = (x), .has_max = RD_BOUND_EX

typedef struct rd_block {
    const char *name; /* OpenAPI component name; NULL = written inline */
    const char *desc;
    int in_opts;            /* offsets are into the analysis' opts, not the scene */
    int items;              /* the block of one array item (offsets into the item;
                                its optional fields default to 0) */
    const rd_field *fields; /* ended by a NULL key */
} rd_block;

/* Every problem of a scene, not only the first (the "errors" of an error
 * answer).  Bounded: at most RD_ISSUES_MAX entries, `dropped` counts the
 * rest.  `allowed` says the allowed values as text ("" when unknown);
 * `did_you_mean` is the closest known key or choice of a misspelt one
 * ("" when none is close). */
#define RD_ISSUES_MAX 50
typedef struct rd_issue {
    int code;
    int range_only; /* out of the table's static range: not an error of its own
                       (core's validators decide; see rd_scene_parse_report) */
    char path[RD_ERROR_PATH_MAX];
    char message[RD_ERROR_MESSAGE_MAX];
    char allowed[160];
    char did_you_mean[48];
} rd_issue;

typedef struct rd_issues {
    int n, dropped;
    rd_issue item[RD_ISSUES_MAX];
} rd_issues;

/* Appends one issue (message from fmt); the list stays bounded. */
void rd_issues_add(rd_issues *list, int code, const char *path, const char *allowed,
                   const char *did_you_mean, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;

/* The allowed values of field `f` as text ("> 0 and <= 5", "one of ...");
 * "" when the table says nothing. */
void rd_schema_allowed(const rd_field *f, char *buf, size_t size);

/* The field the JSON Pointer `path` names under `block` (array indices of
 * item blocks skipped), or NULL. */
const rd_field *rd_schema_find(const rd_block *block, const char *path);

/* The closest of `names` (NULL-ended) to `word` by edit distance
 * (insertions, deletions, substitutions and swaps of neighbours), when it
 * is close enough to be a likely typo: at most 1 edit for words up to 5
 * bytes, 2 up to 10, 3 beyond.  NULL when none is. */
const char *rd_schema_closest(const char *word, const char *const *names);

/* Parses the JSON object `obj` at JSON Pointer `path` into scene `s` by
 * `block`: unknown keys first (listing `block`'s keys as known), then
 * every present field in table order.  `also` (may be NULL) names keys
 * the caller has refused already (rd_scene.c: blocks the analysis does
 * not read): they are not reported again.  The first error goes to `err` (first error wins); the
 * parse goes on after an error, and when s->issues is set every problem
 * found is also listed there, together with values outside the table's
 * static ranges (listed only: core's validators decide about values). */
int rd_schema_parse(struct json_t *obj, const rd_block *block, const char *const *also,
                    const char *path, struct rd_scene *s, rd_error *err);

/* Adds the echo of `block` (every field, defaults filled, optional blocks
 * only when given, RD_F_STRING only when set) to `out`.  0, or -1 on out
 * of memory. */
int rd_schema_echo(const rd_block *block, const struct rd_scene *s, struct json_t *out);

/* The OpenAPI schema of one field; `defaults` is a defaults-filled scene
 * (the source of "default").  Named blocks become a $ref, and their
 * component is added to `components` if missing.  New reference, NULL on
 * out of memory. */
struct json_t *rd_schema_field_openapi(const rd_field *f, const rd_block *in,
                                       const struct rd_scene *defaults, struct json_t *components);

/* The OpenAPI object schema of `block` (type, description,
 * additionalProperties false, properties, required). */
struct json_t *rd_schema_block_openapi(const rd_block *block, const struct rd_scene *defaults,
                                       struct json_t *components);

/* Length of the valid UTF-8 sequence at s (1..4), or 0 if it is not one
 * (overlong forms and surrogates included, as jansson rejects them too). */
int rd_schema_utf8_len(const unsigned char *s);

/* Messages quote user text: `"text"` cut to a readable length. */
void rd_schema_quote(char *buf, size_t size, const char *s);
/* "<path> must be <want>, got <what v is>" (RD_EINVAL). */
int rd_schema_type_error(rd_error *err, const char *path, const char *want, const struct json_t *v);
/* parent + "/" + key as a JSON Pointer (RFC 6901 escapes). */
void rd_schema_path_join(char *out, size_t size, const char *parent, const char *key);
/* The JSON value of `v` described for a message (type and value). */
void rd_schema_describe(const struct json_t *v, char *buf, size_t size);

#endif
