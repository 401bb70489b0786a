/* rd_error — the status table and the first-error-wins record (rd_error.h). */
#include "rd_error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void rd_error_init(rd_error *err)
{
    if (!err)
        return;
    err->code = RD_OK;
    err->path[0] = '\0';
    err->message[0] = '\0';
    err->base[0] = '\0';
}

size_t rd_error_enter(rd_error *err, const char *block)
{
    if (!err)
        return 0;
    size_t mark = strlen(err->base);
    snprintf(err->base + mark, sizeof err->base - mark, "%s", block ? block : "");
    return mark;
}

void rd_error_leave(rd_error *err, size_t mark)
{
    if (err && mark < sizeof err->base)
        err->base[mark] = '\0';
}

void rd_error_init_local(rd_error *local, const rd_error *err)
{
    rd_error_init(local);
    rd_error_enter(local, err ? err->base : "");
}

int rd_error_forward(rd_error *dst, const rd_error *src)
{
    if (dst && dst->code == RD_OK && src->code != RD_OK) {
        dst->code = src->code;
        memcpy(dst->path, src->path, sizeof dst->path);
        memcpy(dst->message, src->message, sizeof dst->message);
    }
    return src->code;
}

/* fmt with each '@' replaced by the base, the base's own '%' doubled. */
static void expand_base(const char *fmt, const char *base, char *out, size_t size)
{
    size_t n = 0;
    for (; *fmt && n + 1 < size; fmt++) {
        if (*fmt != '@') {
            out[n++] = *fmt;
            continue;
        }
        for (const char *b = base; *b && n + 2 < size; b++) {
            if (*b == '%')
                out[n++] = '%';
            out[n++] = *b;
        }
    }
    out[n] = '\0';
}

int rd_error_setv(rd_error *err, int code, const char *path, const char *fmt, va_list ap)
{
    if (!err || err->code != RD_OK)
        return code;
    err->code = code;
    snprintf(err->path, sizeof err->path, "%s%s", err->base, path ? path : "");
    if (!strchr(fmt, '@')) {
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        return code;
    }
    char f[2 * RD_ERROR_MESSAGE_MAX];
    expand_base(fmt, err->base, f, sizeof f);
    vsnprintf(err->message, sizeof err->message, f, ap);
    return code;
}

int rd_error_set(rd_error *err, int code, const char *path, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rd_error_setv(err, code, path, fmt, ap);
    va_end(ap);
    return code;
}

const char *rd_error_code_name(int code)
{
    switch (code) {
#define RD_NAME_(name, value, str, summary) \
    case RD_##name:                         \
        return str;
        RD_ERRNO_MAP(RD_NAME_)
#undef RD_NAME_
    }
    return "unknown_error";
}

const char *rd_error_summary(int code)
{
    switch (code) {
#define RD_SUMMARY_(name, value, str, summary) \
    case RD_##name:                            \
        return summary;
        RD_ERRNO_MAP(RD_SUMMARY_)
#undef RD_SUMMARY_
    }
    return "unknown error";
}

int rd_monitor_report(const rd_monitor *mon, double fraction, rd_error *err)
{
    if (!mon || !mon->report)
        return RD_OK;
    if (mon->report(mon->ctx, fraction) != 0)
        return rd_error_set(err, RD_ECANCELED, "", "The job was stopped before it finished.");
    return RD_OK;
}

static int span_report(void *ctx, double fraction)
{
    const rd_monitor_span *s = ctx;
    fraction = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
    return s->parent->report(s->parent->ctx, s->f0 + (s->f1 - s->f0) * fraction);
}

const rd_monitor *rd_monitor_span_init(rd_monitor_span *s, const rd_monitor *parent, double f0,
                                       double f1)
{
    *s = (rd_monitor_span){parent, f0, f1, {span_report, s}};
    return parent && parent->report ? &s->mon : NULL;
}

int rd_error_range(double v, double lo, double hi, const char *path, const char *unit,
                   rd_error *err)
{
    if (isfinite(v) && v >= lo && v <= hi)
        return RD_OK;
    const char *sp = unit && unit[0] ? " " : ""; /* no unit: no stray spaces */
    unit = unit ? unit : "";
    return rd_error_set(err, RD_EINVAL, path,
                        "%s%s = %g%s%s is out of range: allowed %g to %g%s%s.",
                        err ? err->base : "", path, v, sp, unit, lo, hi, sp, unit);
}

int rd_error_range_in(const char *block, double v, double lo, double hi, const char *path,
                      const char *unit, rd_error *err)
{
    size_t m = rd_error_enter(err, block);
    int rc = rd_error_range(v, lo, hi, path, unit, err);
    rd_error_leave(err, m);
    return rc;
}
