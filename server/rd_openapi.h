/*
 * rd_openapi — server/openapi.json, embedded at build time.
 *
 * The build (server/embed.cmake) turns openapi.json into rd_openapi.c, so the
 * binary serves GET /api/v1/openapi.json with no file to install; the
 * document's "@RINGDYN_VERSION@" is replaced by the project version.  It holds
 * everything but the scene schemas, which rd_api_openapi_json writes into it
 * from the api's tables (api/rd_registry.h) when the document is served.
 */
#ifndef RD_OPENAPI_H
#define RD_OPENAPI_H

#include <stddef.h>

/* The document, NUL-terminated; rd_openapi_json_len excludes the NUL. */
extern const char rd_openapi_json[];
extern const size_t rd_openapi_json_len;

#endif
