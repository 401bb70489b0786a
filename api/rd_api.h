/*
 * rd_api — the JSON face of ringdyn: scenes in, results out (../shared/API.md).
 *
 * Maps a JSON scene to core structs (type checks here, range checks in core's
 * *_validate functions, whose messages and JSON-Pointer paths are passed on
 * unchanged), runs the analysis, and writes the result as JSON or CSV.
 * Knows nothing of HTTP: rd_api_http_status() is only the table that maps a
 * status to the HTTP code the contract promises.  Links core + jansson.
 *
 * Every returned char* is malloc'd and owned by the caller (free()).
 * No global state: every function may be called from any thread, and a
 * parsed scene is never modified, so it may be run on another thread.
 */
#ifndef RD_API_H
#define RD_API_H

#include <stddef.h>
#include <stdio.h>

#include "rd_error.h"

/* Size limits a scene may not exceed (422 limit_exceeded beyond them). */
#define RD_API_BODY_MAX (1024 * 1024) /* bytes, 413 in the server */

/* A parsed, validated, defaults-filled scene.  Opaque. */
typedef struct rd_scene rd_scene;

/* Parses and validates a scene.  On success *out owns a new scene (free with
 * rd_scene_free).  Errors: RD_EJSON (not JSON / not an object, 400),
 * RD_EINVAL or RD_ELIMIT (valid JSON, invalid scene, 422) with `path`,
 * RD_ETOOLARGE (len > RD_API_BODY_MAX; the server refuses those earlier).
 * Unknown keys in the blocks the analysis reads are errors (typos must not
 * pass silently), and so are blocks it does not read (RD_EINVAL at their
 * path, naming the block and the analysis). */
int rd_scene_parse(const char *body, size_t len, rd_scene **out, rd_error *err);
void rd_scene_free(rd_scene *scene);

/* "modal", ... */
const char *rd_scene_analysis(const rd_scene *scene);

/* The echoed scene: defaults filled, only the blocks the analysis reads. */
char *rd_scene_to_json(const rd_scene *scene);

/* Runs the analysis.  On success *result_json is the `result` object of
 * API.md ({"analysis", "scene", "numerics", ...}).  `mon` may be NULL; a monitor
 * that asks to stop makes the run return RD_ECANCELED.  Failures during the run
 * (RD_ENOCONV, RD_ENUMERIC, ...) come with a message saying where and why.
 * A stopped run that finished part of its work (a lift run's whole cycles)
 * returns its error code AND a partial result ("partial": true): the caller
 * frees *result_json whatever the code. */
int rd_scene_run(const rd_scene *scene, const rd_monitor *mon, char **result_json, rd_error *err);

/* A result built once, as data, from which both its JSON text and its CSV
 * table are written (no re-parsing).  Opaque; free with rd_result_doc_free. */
typedef struct rd_result_doc rd_result_doc;

/* rd_scene_run, keeping the result as a document (*out, caller frees; set
 * also with a non-OK code when the run returned a partial result). */
int rd_scene_run_doc(const rd_scene *scene, const rd_monitor *mon, rd_result_doc **out,
                     rd_error *err);
/* The result's JSON text (what rd_scene_run returns); NULL when out of memory. */
char *rd_result_doc_json(const rd_result_doc *doc);
/* The result's main table as CSV (see rd_api_result_csv); NULL + err. */
char *rd_result_doc_csv(const rd_result_doc *doc, rd_error *err);
void rd_result_doc_free(rd_result_doc *doc);

/* The main table of a result as CSV (header row with units), from the JSON
 * text that rd_scene_run produced; only the members the table reads are
 * decoded.  NULL + err on a malformed input (RD_EINTERNAL) or for an
 * analysis without a table (RD_ENOTFOUND).
 * modal: mode,kind,frequency_hz,error_estimate,frequency_extrapolated_hz,
 * in_plane_energy_fraction; reals as %.10g, an empty cell for null. */
char *rd_api_result_csv(const char *result_json, rd_error *err);

/* The OpenAPI document: `template_json` (the non-scene parts: paths,
 * results, errors) with the scene schemas written from the same tables
 * that parse scenes (types, defaults, ranges, enums, descriptions).
 * NULL + err (RD_EINTERNAL: the template is not an OpenAPI object;
 * RD_ENOMEM). */
char *rd_api_openapi_json(const char *template_json, rd_error *err);

/* rd_scene_parse that teaches: on failure *error_json (when error_json is
 * not NULL; caller frees, NULL when out of memory) is the whole error body,
 *   {"error": {...},            the first problem, as rd_api_error_json
 *    "errors": [{"code", "path", "message", "value", "allowed",
 *                "did_you_mean"}, ...],
 *    "errors_omitted": n}      (only when more than RD_ISSUES_MAX were found)
 * where errors[0] is `error` itself and the others are every further
 * problem the schema tables find (JSON types, unknown keys with the closest
 * known key when one is close, values outside the tables' static ranges),
 * core's validator error among them; "value" (the offending JSON value),
 * "allowed" (text) and "did_you_mean" appear when known.  On success
 * *error_json is NULL. */
int rd_scene_parse_report(const char *body, size_t len, rd_scene **out, rd_error *err,
                          char **error_json);

/* rd_scene_parse_report of a body posted to a study's own path
 * (POST /api/v1/calibrations: `analysis` "calibration"): a JSON object
 * without "analysis" is taken as that analysis; one that names another is
 * refused (RD_EREQUEST at /analysis, 400).  `analysis` NULL: exactly
 * rd_scene_parse_report. */
int rd_scene_parse_report_as(const char *body, size_t len, const char *analysis, rd_scene **out,
                             rd_error *err, char **error_json);

/* {"error": {"code": "...", "message": "...", "path": "..."}}; path omitted when empty. */
char *rd_api_error_json(const rd_error *err);

/* HTTP status the contract gives a status code: RD_OK 200, RD_EJSON and RD_EREQUEST 400,
 * RD_ENOTFOUND 404, RD_EMETHOD 405, RD_ETOOLARGE 413, RD_EMEDIA 415,
 * RD_EINVAL and RD_ELIMIT 422, RD_EBUSY 429, RD_ENOMEM 503, anything else 500.
 * (Solver failures and cancellations end a job `failed`/`cancelled`; they are
 * reported inside the job, not as the HTTP status of a request.) */
int rd_api_http_status(int code);

/* The example scenes in `dir` (*.json, each a scene object optionally carrying
 * top-level "name" and "description"): {"examples": [{"name", "description",
 * "scene"}...]} sorted by name.  "name" is the file name without .json (the
 * key for rd_api_example_scene), "description" the scene's own or "", and
 * "scene" the file's object as written.  Each file is validated with
 * rd_scene_parse; an invalid example is an error (RD_EINVAL naming the file,
 * `path` into the scene), and so is a file name that could not be served
 * (not A-Z a-z 0-9 _ - before .json) or a file over RD_API_BODY_MAX.
 * Hidden files and non-regular files are skipped.  An unreadable `dir` is
 * RD_EINTERNAL (a server configuration problem). */
char *rd_api_examples_json(const char *dir, rd_error *err);

/* One example's scene by name (the file name without .json), or NULL with
 * err->code RD_EREQUEST if the name is not valid UTF-8 or holds a control
 * character (malformed, 400), RD_ENOTFOUND if there is no such example or the name has another
 * character than A-Z a-z 0-9 _ - (so no name can leave `dir`; 404), and
 * RD_EINVAL if the file is not a valid scene (the server's fault).  This is
 * the one rule for example names: the server asks nothing else. */
char *rd_api_example_scene(const char *dir, const char *name, rd_error *err);

/* The same JSON text indented by two spaces, for people (the CLI); reals
 * keep up to 15 significant digits.  NULL if `json` is not JSON. */
char *rd_api_json_pretty(const char *json);

/* Reads all of `f` (at most `max` bytes) into a new NUL-terminated buffer
 * (*buf, caller frees; *len excludes the NUL).  Returns RD_OK, RD_ETOOLARGE
 * (more than max bytes), RD_ENOMEM or RD_EREQUEST (read error).  Sets no
 * message: the caller knows what it was reading and says so. */
int rd_api_read_stream(FILE *f, size_t max, char **buf, size_t *len);

/* Library version string. */
const char *rd_api_version(void);

#endif
