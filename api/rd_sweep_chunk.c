/*
 * rd_sweep_chunk — a chunk file read back as the rows its process made
 * (rd_sweep.h, rd_sweep_chunk_read), for a service that runs its sweeps as
 * cluster tasks and builds the table itself.
 *
 * The file is rd_sweep_chunk_head(), then the rows one a line with "," after
 * every row but the last, then "]}" (cli/rd_sweep_cli.c writes it so).  A
 * row is compact JSON and holds no raw newline (JSON escapes it inside
 * strings), so each line is one row, byte for byte the text
 * rd_sweep_run_point gave: the table built from these rows is the table the
 * service's own workers would have made.  The head must equal this sweep's
 * (format, spec hash, points, chunk, chunks, range, columns), so a file of
 * another spec or another split is refused rather than mixed in.
 */
#include "rd_sweep.h"

#include <errno.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The file at `path` as one string, at most `max` bytes; NULL + errno. */
static char *slurp(const char *path, size_t max, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (cap - n < 4096) {
            size_t want = cap ? cap * 2 : 65536;
            char *t = want <= max + 1 ? realloc(text, want + 1) : NULL;
            if (!t) {
                free(text);
                fclose(f);
                errno = want > max + 1 ? EFBIG : ENOMEM;
                return NULL;
            }
            text = t;
            cap = want;
        }
        size_t got = fread(text + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(text);
        errno = EIO;
        return NULL;
    }
    text[n] = '\0';
    *len = n;
    return text;
}

/* Cuts the rows after the head into rows[0..count): each a malloc'd copy. */
static const char *split_rows(char *p, size_t count, char **rows)
{
    for (size_t r = 0; r < count; r++) {
        char *nl = strchr(p, '\n');
        if (!nl)
            return "it ends inside its rows";
        size_t n = (size_t)(nl - p);
        int last = r + 1 == count;
        if (!last && (n == 0 || p[n - 1] != ','))
            return "a row does not end with a comma";
        n -= !last;
        json_t *row = json_loadb(p, n, 0, NULL);
        int ok = json_is_array(row);
        json_decref(row);
        if (!ok)
            return "a row is not a JSON array";
        if ((rows[r] = malloc(n + 1)) == NULL)
            return "out of memory";
        memcpy(rows[r], p, n);
        rows[r][n] = '\0';
        p = nl + 1;
    }
    return strcmp(p, "]}\n") == 0 ? NULL : "it does not end after its rows";
}

int rd_sweep_chunk_read(const rd_sweep *s, const char *dir, size_t c, size_t k, char **rows,
                        rd_error *err)
{
    size_t first, end, len = 0;
    if (rd_sweep_chunk_range(s, c, k, &first, &end, err) != RD_OK)
        return err->code;
    char *name = rd_sweep_chunk_name(c, k), *head = rd_sweep_chunk_head(s, c, k);
    size_t size = strlen(dir) + 80;
    char *path = malloc(size), *text = NULL;
    int rc = name && head && path ? RD_OK : rd_error_set(err, RD_ENOMEM, "", "out of memory");
    if (rc == RD_OK) {
        snprintf(path, size, "%s/%s", dir, name);
        text = slurp(path, RD_SWEEP_CHUNK_FILE_MAX, &len);
        if (!text)
            rc = rd_error_set(err, errno == ENOENT ? RD_ENOTFOUND : RD_EREQUEST, "",
                              "cannot read %s: %s", path, strerror(errno));
    }
    const char *why = NULL;
    size_t hn = head ? strlen(head) : 0;
    if (rc == RD_OK && (len < hn || memcmp(text, head, hn) != 0))
        why = "its head differs from this sweep's chunk (another spec, split or version)";
    else if (rc == RD_OK)
        why = split_rows(text + hn, end - first, rows + first);
    if (rc == RD_OK && why) {
        for (size_t i = first; i < end; i++) {
            free(rows[i]);
            rows[i] = NULL;
        }
        rc = rd_error_set(err, strcmp(why, "out of memory") ? RD_EINVAL : RD_ENOMEM, "",
                          "chunk file %s cannot be used: %s", path, why);
    }
    free(text);
    free(name);
    free(head);
    free(path);
    return rc;
}
