/*
 * rd_sweep — many scenes from one spec: expansion, running one point, and the
 * table of results (issue 16).  Links only the public scene functions
 * (rd_scene_parse_value, rd_scene_run); knows nothing of HTTP or files except
 * the chunk files of rd_sweep_reduce.
 *
 * The spec (JSON object; unknown keys are errors):
 *   {"base": {scene},
 *    "parameters": [{"path": P, one of
 *        "values": [v0, v1, ...]                          any JSON values
 *        "range":  {"start": a, "stop": b, "count": n,
 *                   "scale": "linear"|"log", "integer": false}
 *        "random": {"min": a, "max": b, "scale": "linear"|"log"}}, ...],
 *    "combine": "product" | "zip" | "latin_hypercube",   default "product"
 *    "samples": S, "seed": s,                            latin_hypercube only
 *    "over": {"path": P, "values" | "range"},            optional (below)
 *    "outputs": [O, ...]}
 * P is a JSON Pointer into the scene; missing objects on the way are created.
 * A range holds a + (b - a) k/(n-1) (linear) or a (b/a)^(k/(n-1)) (log, a and
 * b > 0), k = 0..n-1, with both endpoints exact; "integer" rounds each value
 * to the nearest integer.  A random parameter needs latin_hypercube.
 *
 * Expansion (point i, 0 <= i < N; the same on every machine):
 *   product: N = prod n_p; the last parameter varies fastest (nested loops in
 *            the order written).
 *   zip:     every parameter has the same n; point i takes the i-th value of each.
 *   latin_hypercube: N = S.  Each parameter p gets a permutation pi_p of 0..S-1
 *            and jitters j_p,i in [0, 1), drawn in parameter order from one
 *            splitmix64 stream seeded with s (per parameter: the S - 1 draws
 *            of a Fisher-Yates shuffle, k = S-1 down to 1, swap with
 *            floor(u (k+1)), then S jitters); u = (pi_p(i) + j_p,i) / S, so
 *            each of the S strata of every parameter is hit exactly once.
 *            random: a + u (b - a) (log: a (b/a)^u); values/range with m
 *            entries: entry floor(u m).
 *   splitmix64 (Steele, Lea, Flood 2014): x += 0x9E3779B97F4A7C15;
 *            z = (x ^ x>>30) * 0xBF58476D1CE4E5B9; z = (z ^ z>>27) *
 *            0x94D049BB133111EB; draw z ^ z>>31; u = (draw >> 11) 2^-53.
 *   The u are bit-identical everywhere; log scales go through libm's pow.
 *
 * Outputs: a JSON Pointer into the result ("/modes/0/frequency_hz"), or an
 * aggregate  max(P) | min(P) | mean(P) | count(P) | all(P)  where P may hold
 * "*" tokens (every element of an array or member of an object): max/min/mean
 * of all numbers P names (arrays are flattened; null when none), all = those
 * numbers as one flat array (for comparing runs), count = the number
 * of values P names, where a P naming one array or object counts its
 * elements: "count(/events)", "max(/lift)", and the largest error estimate of
 * all modes is "max(/modes/X/error_estimate)" with X replaced by a star.
 * A pointer that names nothing in a result gives null.
 *
 * Validation, before anything runs (first error wins, path into the spec):
 * spec shape and types; the base is a valid scene (paths "/base/..."); each
 * parameter path, with each of its values applied alone to the base, gives a
 * valid scene that reads that path (a path the analysis ignores, a misspelt
 * field or a value outside the scene's range is an error naming the parameter
 * and the scene's own message); ranges with count <= 1000 have every value
 * tried, longer ranges their endpoints; random designs their min and max.
 * Before those, every number of every range and random parameter (all
 * entries, all samples) must be finite, and above 0 on a log scale: finite
 * endpoints whose difference (linear) or ratio (log) is beyond a double give
 * +-inf or NaN inside, and such a spec is refused (RD_EINVAL, 422, path
 * "/parameters/<p>/range" or ".../random").
 * Combinations of values can still be invalid: those points are rows with
 * their error (a failed point never fails the sweep).  So every point is
 * refused up front or is a row of the table: rows = points.
 *
 * The table: {"columns": [...], "rows": [[...], ...]}, columns = the
 * parameter paths, then the outputs as written, then "status" ("ok" or the
 * error code of the point, e.g. "not_converged") and "error" (null or the
 * message, with the field path when there is one).  Rows are in point order.
 *
 * Over (issue 42): with "over": {"path": P, "values": [...] | "range": {...}}
 * (a parameter's forms, no random) every point is run once per over value
 * v_0..v_{m-1} (written at P after the point's parameters), and each output
 * O has five columns instead of one, in this order and with these names:
 *   "min:O", "max:O"   the smallest / largest O over the m runs,
 *   "mean:O"           their mean (a real),
 *   "argmin:O", "argmax:O"  the over value (as JSON, the value itself) of
 *                      the first run reaching the min / max.
 * "parameters" may then be left out (or []): the sweep has one point.  A
 * point is ok only when all its m runs are: the first run that fails (over
 * order) gives the point its status and the message "over P = v: <why>",
 * with null aggregates (the runs after it are not made).  O null in any run
 * (a pointer naming nothing) gives five nulls; O neither a number nor null
 * (a pointer to a string or array) fails the point (invalid_request naming
 * O).  all(P) outputs are refused up front.  P is validated like a parameter
 * (errors at /over/values/k or /over/range) and may be neither a
 * parameter's path nor hold one (/over/path).  Limits count runs = points x
 * m (the message says so); chunks hold whole points; progress counts runs.
 * Reals in rows are written with 15 significant digits (RD_SWEEP_REAL_DIGITS):
 * every value a person types survives, and a table reads the same everywhere.
 */
#ifndef RD_SWEEP_H
#define RD_SWEEP_H

#include <stddef.h>
#include <stdio.h>

#include "rd_error.h"

/* Hard ceilings: runs of one sweep, points x over values (the CLI's limit;
 * a service passes a lower one), parameters, outputs, and S * parameters of a Latin hypercube
 * (its design is held in memory, 8 bytes per entry). */
#define RD_SWEEP_POINTS_MAX      1000000
#define RD_SWEEP_PARAMS_MAX      32
#define RD_SWEEP_OUTPUTS_MAX     64
#define RD_SWEEP_LHS_ENTRIES_MAX 8000000
#define RD_SWEEP_REAL_DIGITS     15
#define RD_SWEEP_OVER_COLUMNS    5 /* min:, max:, mean:, argmin:, argmax: per output */

typedef struct rd_sweep rd_sweep; /* a parsed, validated spec; opaque, read-only */

/* Parses and validates a spec.  `max_points` (clamped to
 * RD_SWEEP_POINTS_MAX) is the caller's limit on runs (points x over values);
 * a sweep above it is refused,
 * and when max_points < RD_SWEEP_POINTS_MAX the message names the cluster
 * path (`ringdyn sweep run`).  Errors: RD_EJSON (not JSON), RD_EREQUEST
 * (400: any other problem of the spec, including a base scene or parameter
 * value the scene schema refuses and too many points) with `path` into the
 * spec, RD_EINVAL (422: a range or random parameter with a non-finite
 * value, above), RD_ETOOLARGE (len > RD_API_BODY_MAX), RD_ENOMEM.  On success *out is
 * a new sweep (rd_sweep_free). */
int rd_sweep_parse(const char *body, size_t len, size_t max_points, rd_sweep **out, rd_error *err);
void rd_sweep_free(rd_sweep *sweep);

/* Number of points N. */
size_t rd_sweep_points(const rd_sweep *sweep);

/* Runs per point: the number of over values, 1 without "over". */
size_t rd_sweep_runs_per_point(const rd_sweep *sweep);

/* 16 hex digits: FNV-1a 64 of the canonical spec (compact JSON, keys sorted,
 * reals with 17 digits).  Borrowed; lives as long as the sweep. */
const char *rd_sweep_hash(const rd_sweep *sweep);

/* The table's columns as a JSON array (caller frees), NULL on out of memory. */
char *rd_sweep_columns_json(const rd_sweep *sweep);

/* The scene of point i (i < N) as JSON text (caller frees); NULL + err
 * (RD_ENOMEM, or RD_EINVAL for i out of range). */
char *rd_sweep_point_scene(const rd_sweep *sweep, size_t i, rd_error *err);

/* Runs point i (once per over value) and writes its table row, a JSON
 * array, to *row (caller frees); `mon` sees the fraction of its runs.  A point whose scene is invalid or whose run fails is still
 * RD_OK: its row carries the status and message.  Returns RD_ECANCELED when
 * `mon` asked to stop (no row: the sweep is being cancelled, not the point),
 * RD_ENOMEM, or RD_EINVAL for i out of range.  `mon` may be NULL; thread-safe
 * (the sweep is only read). */
int rd_sweep_run_point(const rd_sweep *sweep, size_t i, const rd_monitor *mon, char **row,
                       rd_error *err);

/* The table JSON {"columns": ..., "rows": [...]} from `n` row texts in point
 * order; NULL entries (points not yet run) are left out.  NULL + err on out of
 * memory or a row that is not a JSON array (RD_EINTERNAL). */
char *rd_sweep_table_json(const rd_sweep *sweep, char *const *rows, size_t n, rd_error *err);

/* The same table as CSV (RFC 4180: CRLF line ends, fields holding a comma,
 * quote, CR or LF quoted with quotes doubled; reals as %.15g, null as an
 * empty field, strings bare, arrays/objects as compact JSON). */
char *rd_sweep_table_csv(const rd_sweep *sweep, char *const *rows, size_t n, rd_error *err);

/* A JSON array (columns or a row) as one CSV record with its CRLF; NULL + err
 * when `array_json` is not a JSON array or memory runs out. */
char *rd_sweep_csv_record(const char *array_json, rd_error *err);

/* A table (JSON text as above, any columns) as CSV; NULL + err when it is not
 * a table or memory runs out. */
char *rd_sweep_csv_from_table(const char *table_json, rd_error *err);

/* ---- fidelity: the speed/accuracy trade of one scene ----------------------
 * A fidelity sweep runs one scene over its fidelity settings with its error
 * estimate switched on: /discretization/segments (default ladder: 5, 10, 20,
 * 40, 80, 160, 320; lift 4, 8, 16, 32), for lift also /numerics/rtol
 * (default 1e-4, 1e-5, 1e-6, 1e-7), and /numerics/model when values are given
 * (refused like any parameter when the scene schema has no such field).
 * Outputs: /numerics/wall_s (the run with its estimate), the error estimate
 * (modal: max(/modes/X/error_estimate) over the modes X; others
 * /numerics/error_estimate) and all(Q) of the compared quantity Q: modal
 * every frequency_hz, pretension /gap_opening_inner, contact
 * /mean_pressure_pa, lift /lift (plus /scene/groove/axial_clearance,
 * /numerics/model/name and /numerics/segments_check). */
typedef struct rd_sweep_fidelity_opts {
    const double *segments; /* NULL: the default ladder */
    size_t n_segments;
    const double *rtol; /* lift only; NULL: the default */
    size_t n_rtol;
    const char *const *models; /* NULL: the scene's own model */
    size_t n_models;
} rd_sweep_fidelity_opts;

/* The spec of a fidelity sweep of `scene` (JSON text; caller frees the
 * spec), to be parsed with rd_sweep_parse.  NULL + err when the scene is
 * invalid (its own error, RD_EINVAL/RD_EJSON) or out of memory. */
char *rd_sweep_fidelity_spec(const char *scene, size_t len, const rd_sweep_fidelity_opts *opts,
                             rd_error *err);

/* The fidelity table from the table of a fidelity sweep: the all(Q) (and
 * lift's clearance and segments_check) columns are replaced by
 *   "error_vs_finest": for each ok row, max_k |q_k - Q_k| / |Q_k| against
 *     the finest ok run (most segments, then smallest rtol), for lift
 *     max_k |q_k - Q_k| / axial clearance, the measure the lift estimate uses;
 *   "estimate_covers": the discretisations the row's estimate covers, words
 *     of "segments time model" separated by spaces (null: no estimate);
 *   "changes": those where the row's setting differs from the finest run's
 *     ("" for the finest run itself);
 *   "basis": "estimate" when the estimate covers every change and is not
 *     below error_vs_finest, else "measured" (null: not comparable);
 *   "error_on_basis": the row's error on that basis (never below what was
 *     measured against the finest run);
 *   "pareto": true for the rows no other row beats in both wall time and
 *     error_on_basis.
 * NULL + err (RD_EINTERNAL) when `table_json` is not a fidelity table. */
char *rd_sweep_fidelity_table(const char *table_json, rd_error *err);

/* ---- chunks: one sweep split over K processes ---------------------------
 * Chunk c of K (0 <= c < K <= N) holds points [c N / K, (c + 1) N / K).  Its
 * file, "chunk-<c>-of-<K>.json" (c and K as 6 digits), is
 *   {"format": "ringdyn-sweep-chunk/1", "spec_hash": h, "points": N,
 *    "chunk": c, "chunks": K, "first": a, "end": b, "columns": [...],
 *    "rows": [row_a, ..., row_{b-1}]}
 * written by the caller as rd_sweep_chunk_head(), the rows separated by ",\n",
 * then "]}\n". */

/* [*first, *end) of chunk c of K; RD_EINVAL (with a message) when c >= K,
 * K == 0 or K > N. */
int rd_sweep_chunk_range(const rd_sweep *sweep, size_t c, size_t k, size_t *first, size_t *end,
                         rd_error *err);

/* File name of chunk c of K (caller frees). */
char *rd_sweep_chunk_name(size_t c, size_t k);

/* Everything of the chunk file before its first row (caller frees). */
char *rd_sweep_chunk_head(const rd_sweep *sweep, size_t c, size_t k);

/* Largest chunk file rd_sweep_chunk_read takes (its rows are held in memory). */
#define RD_SWEEP_CHUNK_FILE_MAX ((size_t)1 << 30)

/* Reads chunk c of K from `dir` (rd_sweep_chunk.c): rows[first..end) of
 * the chunk get the rows as its process wrote them, byte for byte the text
 * rd_sweep_run_point gave (caller frees each); `rows` has the sweep's N
 * entries and the others are not touched.  RD_ENOTFOUND: no such file;
 * RD_EINVAL: the file is not this sweep's chunk c of K or is damaged (rows
 * left NULL); RD_EREQUEST: it cannot be read; RD_ENOMEM. */
int rd_sweep_chunk_read(const rd_sweep *sweep, const char *dir, size_t c, size_t k, char **rows,
                        rd_error *err);

/* Reads every chunk file of `dir` and writes the whole table to `out`, as
 * JSON or (csv != 0) CSV, streaming one chunk at a time (memory bounded by
 * the largest chunk).  Before writing anything it checks that the chunks of
 * one K are all there (RD_ENOTFOUND naming the missing ones), come from one
 * spec (same spec_hash and columns; RD_EINVAL otherwise) and hold exactly their
 * rows.  RD_EREQUEST when dir cannot be read or output cannot be written. */
int rd_sweep_reduce(const char *dir, int csv, FILE *out, rd_error *err);

#endif
