/*
 * rd_openapi_doc — server/openapi.json, embedded at build time.
 *
 * The build (api/embed.cmake) turns openapi.json into rd_openapi_doc.c, in
 * the api library: the server serves GET /api/v1/openapi.json with no file
 * to install, and the api checks result pointers against its result schemas
 * (rd_result_schema.h); the
 * document's "@RINGDYN_VERSION@" is replaced by the project version.  It holds
 * everything but the scene schemas, which rd_api_openapi_json writes into it
 * from the api's tables (api/rd_registry.h) when the document is served.
 */
#ifndef RD_OPENAPI_DOC_H
#define RD_OPENAPI_DOC_H

#include <stddef.h>

/* The document, NUL-terminated; rd_openapi_json_len excludes the NUL. */
extern const char rd_openapi_json[];
extern const size_t rd_openapi_json_len;

#endif
