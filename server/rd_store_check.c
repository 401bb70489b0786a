/* rd_store_check — the store's files at start (rd_store_check.h). */
#define _XOPEN_SOURCE 700

#include "rd_store_check.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define WAL_HEADER       32
#define WAL_FRAME_HEADER 24

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

/* SQLite's WAL checksum over n bytes (n a multiple of 8), continuing s[2]:
 * s0 += x[i] + s1; s1 += x[i+1] + s0 over pairs of 32-bit words. */
static void wal_sum(int big, const unsigned char *p, size_t n, uint32_t s[2])
{
    for (size_t i = 0; i + 8 <= n; i += 8) {
        s[0] += (big ? be32(p + i) : le32(p + i)) + s[1];
        s[1] += (big ? be32(p + i + 4) : le32(p + i + 4)) + s[0];
    }
}

/* The frames after the header: replayed commits, and where replay stops.
 * Returns the commit frames of any generation. */
static long scan_frames(FILE *f, const unsigned char *h, unsigned char *frame, size_t page,
                        rd_store_wal *out)
{
    int big = be32(h) & 1, broken = 0;
    long all = 0;
    uint32_t s[2] = {be32(h + 24), be32(h + 28)};
    while (fread(frame, 1, WAL_FRAME_HEADER + page, f) == WAL_FRAME_HEADER + page) {
        out->frames++;
        int ours = memcmp(frame + 8, h + 16, 8) == 0, commit = be32(frame + 4) != 0;
        all += commit;
        if (!broken) {
            uint32_t t[2] = {s[0], s[1]};
            wal_sum(big, frame, 8, t);
            wal_sum(big, frame + WAL_FRAME_HEADER, page, t);
            if (ours && t[0] == be32(frame + 16) && t[1] == be32(frame + 20)) {
                s[0] = t[0];
                s[1] = t[1];
                out->commits += commit;
                continue;
            }
            broken = 1;
            out->first_bad = out->frames;
        }
        out->lost_commits += ours && commit;
    }
    if (out->lost_commits == 0)
        out->first_bad = 0; /* a clean end: stale frames of an older generation */
    return all;
}

int rd_store_wal_scan(const char *file, rd_store_wal *out, rd_error *err)
{
    char path[4200];
    memset(out, 0, sizeof *out);
    snprintf(path, sizeof path, "%s-wal", file);
    FILE *f = fopen(path, "rb");
    if (!f)
        return errno == ENOENT ? RD_OK
                               : rd_error_set(err, RD_EINTERNAL, "", "cannot read %s: %s", path,
                                              strerror(errno));
    unsigned char h[WAL_HEADER];
    size_t got = fread(h, 1, sizeof h, f);
    unsigned char *frame = NULL;
    if (got == 0) {
        fclose(f);
        return RD_OK;
    }
    uint32_t magic = got == sizeof h ? be32(h) : 0, page = got == sizeof h ? be32(h + 8) : 0;
    uint32_t s[2] = {0, 0};
    wal_sum(magic & 1, h, 24, s);
    int page_ok = page >= 512 && page <= 65536 && (page & (page - 1)) == 0;
    out->header_bad = (magic != 0x377f0682 && magic != 0x377f0683) || !page_ok ||
                      s[0] != be32(h + 24) || s[1] != be32(h + 28);
    if (!page_ok)
        page = 4096; /* the header is unreadable: count frames of SQLite's default page */
    frame = malloc(WAL_FRAME_HEADER + page);
    long all = frame ? scan_frames(f, h, frame, page, out) : 0;
    if (out->header_bad) { /* every frame is dropped, those of older generations too */
        out->lost_commits = all;
        out->commits = 0;
        out->first_bad = 1;
    }
    free(frame);
    fclose(f);
    return RD_OK;
}

/* "<UTC time>" as 20261202T104200Z. */
static void stamp(char *buf, size_t n)
{
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(buf, n, "%Y%m%dT%H%M%SZ", &tm);
}

/* Copies `from` to `to` (a new file); 0 or -1. */
static int copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wxb") : NULL;
    char buf[65536];
    size_t n;
    int rc = in && out ? 0 : -1;
    while (rc == 0 && (n = fread(buf, 1, sizeof buf, in)) > 0)
        rc = fwrite(buf, 1, n, out) == n ? 0 : -1;
    if (in)
        fclose(in);
    if (out && fclose(out) != 0)
        rc = -1;
    return rc;
}

void rd_store_check_wal(const char *file, char *report, size_t n)
{
    rd_store_wal w;
    rd_error err;
    rd_error_init(&err);
    report[0] = '\0';
    if (rd_store_wal_scan(file, &w, &err) != RD_OK) {
        snprintf(report, n, "job store: %s; what it holds may be lost", err.message);
        return;
    }
    if (w.lost_commits == 0)
        return;
    char when[32], wal[4200], copy[4300];
    stamp(when, sizeof when);
    snprintf(wal, sizeof wal, "%s-wal", file);
    snprintf(copy, sizeof copy, "%s.damaged-%s", wal, when);
    for (int k = 2; access(copy, F_OK) == 0 && k < 100; k++)
        snprintf(copy, sizeof copy, "%s.damaged-%s-%d", wal, when, k);
    int copied = copy_file(wal, copy) == 0;
    snprintf(report, n,
             "job store: the WAL %s is damaged %s%ld of its %ld frames: the last %ld committed "
             "write%s (jobs submitted or finished just before the server stopped) cannot be "
             "replayed and are lost; the %ld commit%s before that point %s kept.  %s%s",
             wal, w.header_bad ? "in its header, so SQLite drops all " : "at frame ",
             w.header_bad ? w.frames : w.first_bad, w.frames, w.lost_commits,
             w.lost_commits == 1 ? "" : "s", w.commits, w.commits == 1 ? "" : "s",
             w.commits == 1 ? "is" : "are", copied ? "A copy is kept as " : "",
             copied ? copy : "(no copy could be kept)");
}

int rd_store_quarantine(const char *file, const char *why, char *report, size_t n, rd_error *err)
{
    char when[32], to[4300], from_wal[4200], to_wal[4400], shm[4200];
    stamp(when, sizeof when);
    snprintf(to, sizeof to, "%s.damaged-%s", file, when);
    for (int k = 2; access(to, F_OK) == 0 && k < 100; k++) /* never over an earlier one */
        snprintf(to, sizeof to, "%s.damaged-%s-%d", file, when, k);
    snprintf(from_wal, sizeof from_wal, "%s-wal", file);
    snprintf(to_wal, sizeof to_wal, "%s-wal", to);
    snprintf(shm, sizeof shm, "%s-shm", file);
    if (rename(file, to) != 0)
        return rd_error_set(err, RD_EINTERNAL, "",
                            "job store %s is damaged (%s) and cannot be moved aside: %s; move or "
                            "remove it, then start again",
                            file, why, strerror(errno));
    if (rename(from_wal, to_wal) != 0 && errno != ENOENT)
        return rd_error_set(err, RD_EINTERNAL, "", "cannot move %s aside: %s", from_wal,
                            strerror(errno));
    (void)unlink(shm); /* rebuilt from the WAL; never holds data of its own */
    snprintf(report, n,
             "job store: %s is damaged (%s): moved aside to %s, and the server starts with an "
             "empty store: the jobs and sweeps it held are not served.  To get back what can be "
             "read: sqlite3 %s .recover | sqlite3 recovered.sqlite3",
             file, why, to, to);
    return RD_OK;
}
