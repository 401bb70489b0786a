/*
 * rd_gzip — gzip (RFC 1952) of a buffer with zlib (Debian zlib1g), for
 * responses to clients that send Accept-Encoding: gzip.
 */
#ifndef RD_GZIP_H
#define RD_GZIP_H

#include <stddef.h>

/* Bodies smaller than this are sent as they are: below it the gzip header
 * and the CPU cost outweigh the bytes saved. */
#define RD_GZIP_MIN_BYTES 1024

/* *out (malloc'd, *out_len bytes) is the gzip of `in`.  0, or -1 when out of
 * memory or zlib fails. */
int rd_gzip(const char *in, size_t len, char **out, size_t *out_len);

/* Does an Accept-Encoding value accept gzip (a "gzip" or "*" coding whose
 * q is not 0)?  NULL: no. */
int rd_gzip_accepted(const char *accept_encoding);

#endif
