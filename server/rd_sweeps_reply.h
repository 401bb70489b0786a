/*
 * rd_sweeps_reply — the answers rd_sweeps.c builds (internal to the server's
 * sweeps module): an error body with its status, a JSON body, a key spliced
 * into a rendered object.
 */
#ifndef RD_SWEEPS_REPLY_H
#define RD_SWEEPS_REPLY_H

#include "rd_error.h"
#include "rd_sweeps.h"

/* The error's body and HTTP status (Retry-After for a full queue). */
void rd_sweeps_reply_error(rd_sweeps_reply *r, const rd_error *err);

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void rd_sweeps_reply_fail(rd_sweeps_reply *r, int code, const char *fmt, ...);

/* `body` (malloc'd, taken) with `status`; NULL: out of memory (500). */
void rd_sweeps_reply_json(rd_sweeps_reply *r, int status, char *body);

void rd_sweeps_reply_not_found(rd_sweeps_reply *r, const char *id);

/* `head` (a JSON object's text) with `,"key":value` inserted before its
 * closing brace; frees head.  NULL when either is NULL or out of memory. */
char *rd_sweeps_splice(char *head, const char *key, const char *value);

#endif
