/*
 * rd_http_static — the web page's files (rd_http_int.h), and the directory
 * options resolved at start.
 *
 * Every file carries the page's security headers: a Content-Security-Policy
 * that runs scripts from this origin only (the page has no inline script or
 * event-handler attribute; an injected one does not run), allows style
 * attributes (the chart export copies computed styles into style="" of the
 * SVG it writes) and data: images (the PNG export draws the SVG through
 * one), and forbids framing (frame-ancestors, and X-Frame-Options for
 * browsers without CSP 2); Referrer-Policy no-referrer.
 */
/* realpath() is XSI: the build defines only _POSIX_C_SOURCE. */
#define _XOPEN_SOURCE 700

#include "rd_http_int.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#define PAGE_CSP                                                                                \
    "default-src 'self'; script-src 'self'; style-src 'self'; style-src-attr 'unsafe-inline'; " \
    "img-src 'self' data: blob:; connect-src 'self'; object-src 'none'; base-uri 'none'; "      \
    "form-action 'self'; frame-ancestors 'none'"

static const char *content_type_for(const char *path)
{
    static const struct {
        const char *ext, *type;
    } types[] = {{"html", "text/html; charset=utf-8"},
                 {"htm", "text/html; charset=utf-8"},
                 {"js", "text/javascript; charset=utf-8"},
                 {"mjs", "text/javascript; charset=utf-8"},
                 {"css", "text/css; charset=utf-8"},
                 {"svg", "image/svg+xml"},
                 {"json", "application/json"},
                 {"png", "image/png"},
                 {"jpg", "image/jpeg"},
                 {"jpeg", "image/jpeg"},
                 {"ico", "image/x-icon"},
                 {"txt", "text/plain; charset=utf-8"},
                 {"csv", "text/csv; charset=utf-8"},
                 {"map", "application/json"},
                 {"woff2", "font/woff2"},
                 {"wasm", "application/wasm"}};
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (dot)
        for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
            if (strcasecmp(dot + 1, types[i].ext) == 0)
                return types[i].type;
    return "application/octet-stream";
}

/* A relative path we are willing to look up: no "..", no backslash, no
 * control character, no empty or dot-led segment (hidden files, ".", ".."),
 * no trailing slash (no directory listings). */
static int static_path_ok(const char *rel)
{
    if (!*rel || strstr(rel, "..") || strchr(rel, '\\') || rd_http_has_control_char(rel) ||
        strlen(rel) >= PATH_MAX)
        return 0;
    for (const char *seg = rel;;) {
        if (*seg == '\0' || *seg == '/' || *seg == '.')
            return 0;
        const char *slash = strchr(seg, '/');
        if (!slash)
            return 1;
        seg = slash + 1;
    }
}

/* GET / (index.html), /static/<path>, and also /<path> for any other path
 * outside /api/ (so a page may use relative links).  Resolved with
 * realpath, which also follows symlinks, and served only when the result is
 * a regular file inside the static dir. */
enum MHD_Result rd_http_serve_static(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                     const char *url, const char *method)
{
    enum MHD_Result ret;
    char *full = NULL, *resolved = NULL;
    int fd = -1;
    const char *rel = url[0] == '/' ? url + 1 : "";
    const char *sub = rd_http_after_prefix(rel, "static/");
    if (sub)
        rel = sub;
    if (url[0] != '/' || strcmp(url, "/static") == 0) {
        ret = rd_http_send_not_found(h, c, rq, url);
        goto out;
    }
    if (*rel == '\0')
        rel = "index.html";
    else if (strcmp(rel, "docs") == 0) /* the API docs page (static/docs.html) */
        rel = "docs.html";
    if (!h->static_root || !static_path_ok(rel)) {
        ret = rd_http_send_not_found(h, c, rq, url);
        goto out;
    }
    size_t root_len = strlen(h->static_root);
    full = malloc(root_len + 1 + strlen(rel) + 1);
    if (!full) {
        ret = rd_http_send_response(h, c, rq, 0, NULL);
        goto out;
    }
    sprintf(full, "%s/%s", h->static_root, rel);
    resolved = realpath(full, NULL);
    if (!resolved || strncmp(resolved, h->static_root, root_len) != 0 ||
        resolved[root_len] != '/') {
        ret = rd_http_send_not_found(h, c, rq, url);
        goto out;
    }
    /* O_NONBLOCK: opening a FIFO someone left in the dir must not hang us. */
    fd = open(resolved, O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ret = rd_http_send_not_found(h, c, rq, url);
        goto out;
    }
    if (!rd_http_method_allowed("GET, HEAD", method)) {
        rd_error err;
        rd_error_init(&err);
        rd_error_set(&err, RD_EMETHOD, "", "Method %.16s is not allowed here; use GET or HEAD.",
                     method);
        ret = rd_http_send_error(h, c, rq, &err, "GET, HEAD");
        goto out;
    }
    struct MHD_Response *r = MHD_create_response_from_fd64((uint64_t)st.st_size, fd);
    if (!r) {
        ret = rd_http_send_response(h, c, rq, 0, NULL);
        goto out;
    }
    fd = -1; /* the response owns it now */
    r = rd_http_with_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, content_type_for(resolved));
    r = rd_http_with_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-cache");
    r = rd_http_with_header(r, "X-Content-Type-Options", "nosniff");
    r = rd_http_with_header(r, "Content-Security-Policy", PAGE_CSP);
    r = rd_http_with_header(r, "X-Frame-Options", "DENY");
    r = rd_http_with_header(r, "Referrer-Policy", "no-referrer");
    ret = rd_http_send_response(h, c, rq, MHD_HTTP_OK, r);
out:
    if (fd >= 0)
        close(fd);
    free(resolved);
    free(full);
    return ret;
}

/* realpath of a directory option, or an error naming the option. */
int rd_http_resolve_dir(const char *option, const char *dir, char **out, rd_error *err)
{
    *out = NULL;
    if (!dir)
        return RD_OK;
    char *path = realpath(dir, NULL);
    struct stat st;
    if (!path || stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        int e = errno;
        free(path);
        return rd_error_set(err, RD_EINVAL, "", "%s %s: not a readable directory (%s).", option,
                            dir, path ? "not a directory" : strerror(e));
    }
    *out = path;
    return RD_OK;
}
