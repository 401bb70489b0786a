/*
 * rd_examples — the shipped example scenes: a directory of <name>.json
 * files, each a scene (optionally with top-level "name" and "description").
 *
 * Implements rd_api_examples_json and rd_api_example_scene (rd_api.h).
 * Every file is validated with the same parser as a submitted scene, so a
 * broken example is caught when it is served (and by the tests), not when
 * someone runs it.
 */
#ifndef RD_EXAMPLES_H
#define RD_EXAMPLES_H

#include "rd_api.h"

/* Longest example name, bytes (without ".json"). */
#define RD_EXAMPLE_NAME_MAX 64
/* Largest example file read, bytes: the request body limit. */
#define RD_EXAMPLE_FILE_MAX RD_API_BODY_MAX

/* 1 if `name` is 1..RD_EXAMPLE_NAME_MAX characters of A-Z a-z 0-9 _ -:
 * the only names served, so a name can never reach outside the directory. */
int rd_examples_name_ok(const char *name);

/* 1 if `name` is not valid UTF-8 or holds a control character (below
 * 0x20, or 0x7f): not a name at all, so a request for it is malformed
 * (400) rather than naming an example that does not exist (404). */
int rd_examples_name_malformed(const char *name);

#endif
