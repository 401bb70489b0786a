/*
 * rd_http_access — who may ask (rd_http_int.h): message framing the handler
 * can still judge, the Host allowlist and the bearer token.
 */
#include "rd_http_int.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>

struct header_scan {
    const char *name;
    int count;
    int differ;        /* two of them have different values */
    const char *first; /* the first value */
};

static enum MHD_Result scan_header(void *cls, enum MHD_ValueKind kind, const char *key,
                                   const char *value)
{
    (void)kind;
    struct header_scan *scan = cls;
    if (strcasecmp(key, scan->name) != 0)
        return MHD_YES;
    if (scan->count++ == 0)
        scan->first = value ? value : "";
    else if (strcmp(scan->first, value ? value : "") != 0)
        scan->differ = 1;
    return MHD_YES;
}

static struct header_scan scan_headers(struct MHD_Connection *c, const char *name)
{
    struct header_scan scan = {name, 0, 0, NULL};
    MHD_get_connection_values(c, MHD_HEADER_KIND, scan_header, &scan);
    return scan;
}

/* Message framing libmicrohttpd lets through but HTTP/1.1 (RFC 9112 6.3)
 * says to refuse, since a proxy in front could read the body differently
 * (request smuggling): Content-Length headers that disagree, Content-Length
 * together with Transfer-Encoding, a transfer coding other than chunked;
 * and an HTTP/1.1 request without Host.  The answer closes the connection,
 * whose remaining bytes cannot be trusted.  Returns MHD_YES (with
 * *refused = 1) after queueing the refusal, or leaves *refused 0. */
enum MHD_Result rd_http_check_framing(rd_http *h, struct MHD_Connection *c, struct request *rq,
                                      const char *version, int *refused)
{
    char buf[64];
    const char *why = NULL;
    struct header_scan length = scan_headers(c, MHD_HTTP_HEADER_CONTENT_LENGTH);
    struct header_scan coding = scan_headers(c, MHD_HTTP_HEADER_TRANSFER_ENCODING);
    struct header_scan host = scan_headers(c, MHD_HTTP_HEADER_HOST);
    char message[256];
    if (length.differ)
        why = "The request has Content-Length headers with different values; send one.";
    else if (length.count > 0 && coding.count > 0)
        why = "The request has both Content-Length and Transfer-Encoding; send one of them.";
    else if (coding.count > 1 || (coding.count == 1 && strcasecmp(coding.first, "chunked") != 0)) {
        snprintf(message, sizeof message,
                 "Transfer-Encoding %s is not supported; send the body as it is or chunked.",
                 rd_http_printable(coding.first, buf, sizeof buf));
        why = message;
    } else if (host.count > 1)
        why = "The request has more than one Host header.";
    else if (host.count == 0 && strcmp(version, MHD_HTTP_VERSION_1_1) == 0)
        why = "An HTTP/1.1 request must carry a Host header.";
    *refused = why != NULL;
    if (!why)
        return MHD_YES;
    return rd_http_send_server_error(h, c, rq, MHD_HTTP_BAD_REQUEST, "invalid_request", why,
                                     MHD_HTTP_HEADER_CONNECTION, "close");
}

/* The name part of a Host header value: "[v6]" with its brackets, or what
 * precedes ":port"; NULL when the port is not all digits or the name is
 * empty or too long.  Lower-cased into buf. */
static const char *host_name(const char *host, char *buf, size_t n)
{
    const char *end;
    if (host[0] == '[') {
        end = strchr(host, ']');
        if (!end)
            return NULL;
        end++;
    } else {
        end = host + strcspn(host, ":");
    }
    if (*end == ':' && (end[1] == '\0' || strspn(end + 1, "0123456789") != strlen(end + 1)))
        return NULL;
    if (*end != '\0' && *end != ':')
        return NULL;
    size_t len = (size_t)(end - host);
    if (len == 0 || len >= n)
        return NULL;
    for (size_t i = 0; i < len; i++)
        buf[i] = (char)((host[i] >= 'A' && host[i] <= 'Z') ? host[i] - 'A' + 'a' : host[i]);
    buf[len] = '\0';
    return buf;
}

/* A request that names no Host (HTTP/1.0; rd_http_check_framing refuses HTTP/1.1
 * without one) is allowed: DNS rebinding needs a browser, and browsers
 * always send Host. */
int rd_http_host_allowed(const rd_http *h, const char *host)
{
    if (!host)
        return 1;
    char buf[256];
    const char *name = host_name(host, buf, sizeof buf);
    if (!name)
        return 0;
    for (size_t i = 0; i < h->n_allow; i++)
        if (strcmp(name, h->allow[i]) == 0)
            return 1;
    return 0;
}

/* Compares in time that depends on the lengths only, not on where they differ. */
static int token_matches(const char *given, size_t given_len, const char *want, size_t want_len)
{
    unsigned char diff = given_len != want_len;
    for (size_t i = 0; i < given_len && i < want_len; i++)
        diff |= (unsigned char)(given[i] ^ want[i]);
    return diff == 0;
}

/* "Bearer TOKEN" (scheme in any case) carrying our token. */
int rd_http_authorized(const rd_http *h, struct MHD_Connection *c)
{
    const char *auth =
        MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_AUTHORIZATION);
    if (!auth || strncasecmp(auth, "Bearer ", 7) != 0)
        return 0;
    const char *t = auth + 7;
    while (*t == ' ')
        t++;
    size_t n = strlen(t);
    while (n > 0 && (t[n - 1] == ' ' || t[n - 1] == '\t'))
        n--;
    return token_matches(t, n, h->token, strlen(h->token));
}

int rd_http_is_loopback(const struct sockaddr_storage *addr)
{
    if (addr->ss_family == AF_INET) {
        const struct sockaddr_in *a4 = (const struct sockaddr_in *)addr;
        return (ntohl(a4->sin_addr.s_addr) >> 24) == 127;
    }
    const struct sockaddr_in6 *a6 = (const struct sockaddr_in6 *)addr;
    return IN6_IS_ADDR_LOOPBACK(&a6->sin6_addr) ||
           (IN6_IS_ADDR_V4MAPPED(&a6->sin6_addr) && a6->sin6_addr.s6_addr[12] == 127);
}

static int is_wildcard(const struct sockaddr_storage *addr)
{
    if (addr->ss_family == AF_INET)
        return ((const struct sockaddr_in *)addr)->sin_addr.s_addr == htonl(INADDR_ANY);
    return IN6_IS_ADDR_UNSPECIFIED(&((const struct sockaddr_in6 *)addr)->sin6_addr);
}

static int add_allowed(rd_http *h, const char *name, rd_error *err)
{
    char buf[256];
    const char *lower = host_name(name, buf, sizeof buf);
    if (!lower || strlen(lower) != strlen(name)) /* a port was given */
        return rd_error_set(
            err, RD_EINVAL, "",
            "--allow-host %s: not a host name (give the name without a port; IPv6 in "
            "brackets).",
            name);
    char **grown = realloc(h->allow, (h->n_allow + 1) * sizeof *grown);
    if (!grown)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->allow = grown;
    if (!(h->allow[h->n_allow] = strdup(lower)))
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    h->n_allow++;
    return RD_OK;
}

/* The Host allowlist (loopback names, the bound address unless it is a
 * wildcard, --allow-host) and a copy of the token. */
int rd_http_set_access(rd_http *h, const rd_http_config *cfg, const struct sockaddr_storage *addr,
                       rd_error *err)
{
    static const char *const loopback[] = {"127.0.0.1", "localhost", "[::1]"};
    int rc = RD_OK;
    for (size_t i = 0; i < sizeof loopback / sizeof loopback[0] && rc == RD_OK; i++)
        rc = add_allowed(h, loopback[i], err);
    if (rc == RD_OK && !is_wildcard(addr))
        rc = add_allowed(h, h->host, err);
    for (int i = 0; i < cfg->n_allow_hosts && rc == RD_OK; i++)
        rc = add_allowed(h, cfg->allow_hosts[i], err);
    if (rc == RD_OK && cfg->token && !(h->token = strdup(cfg->token)))
        rc = rd_error_set(err, RD_ENOMEM, "", "Out of memory.");
    return rc;
}
