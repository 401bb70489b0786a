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
}

int rd_error_setv(rd_error *err, int code, const char *path, const char *fmt, va_list ap)
{
    if (!err || err->code != RD_OK)
        return code;
    err->code = code;
    snprintf(err->path, sizeof err->path, "%s", path ? path : "");
    vsnprintf(err->message, sizeof err->message, fmt, ap);
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
    return rd_error_set(err, RD_EINVAL, path, "%s = %g%s%s is out of range: allowed %g to %g%s%s.",
                        path, v, sp, unit, lo, hi, sp, unit);
}
