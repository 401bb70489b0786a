/*
 * rd_study — the base scene, its variations and their runs on threads,
 * shared by calibrations and sensitivities (rd_study.h).
 */
#include "rd_study.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rd_jsonptr.h"
#include "rd_result_schema.h"
#include "rd_scene.h"

static int is_study(const char *analysis)
{
    return strcmp(analysis, "calibration") == 0 || strcmp(analysis, "sensitivity") == 0;
}

int rd_study_keep(json_t **slot, int *given, json_t *v, const char *path, rd_error *err)
{
    json_decref(*slot);
    *slot = json_deep_copy(v);
    *given = 1;
    return *slot ? RD_OK : rd_error_set(err, RD_ENOMEM, path, "out of memory for %s", path);
}

json_t *rd_study_echo(json_t *kept)
{
    return kept ? json_incref(kept) : json_null();
}

int rd_study_base_parse(json_t *v, const struct rd_scene_ops *ops, rd_study_base *b, rd_error *err)
{
    memset(b, 0, sizeof *b);
    b->ops = ops;
    if (!json_is_object(v))
        return rd_error_set(err, RD_EREQUEST, "/base",
                            "/base must be a scene object, such as "
                            "{\"analysis\": \"ringpack\"}");
    const char *a = json_string_value(json_object_get(v, "analysis"));
    if (a && is_study(a))
        return rd_error_set(err, RD_EREQUEST, "/base/analysis",
                            "/base/analysis is \"%s\": the base of a study is a scene of one "
                            "analysis (modal, pretension, contact, lift, ringpack), not a study",
                            a);
    rd_scene *sc = NULL;
    rd_error e;
    rd_error_init(&e);
    if (ops->parse_value(v, &sc, &e) != RD_OK) {
        char path[RD_ERROR_PATH_MAX + 8];
        snprintf(path, sizeof path, "/base%s", e.path);
        return rd_error_set(err, e.code == RD_ENOMEM ? RD_ENOMEM : RD_EREQUEST, path,
                            "/base is not a valid scene: %s", e.message);
    }
    b->an = sc->an;
    b->echo = rd_scene_echo(sc);
    ops->free(sc);
    b->scene = json_deep_copy(v);
    if (!b->echo || !b->scene) {
        rd_study_base_cleanup(b);
        return rd_error_set(err, RD_ENOMEM, "/base", "out of memory for the base scene");
    }
    return RD_OK;
}

void rd_study_base_cleanup(rd_study_base *b)
{
    json_decref(b->scene);
    json_decref(b->echo);
    b->scene = b->echo = NULL;
}

int rd_study_number_at(const rd_study_base *b, const char *ptr, const char *path, double *value,
                       rd_error *err)
{
    if (!ptr || ptr[0] != '/' || !rd_jsonptr_valid(ptr))
        return rd_error_set(err, RD_EREQUEST, path,
                            "%s must be a JSON Pointer into the base scene (\"/ring/closed_gap\")",
                            path);
    json_t *v = rd_jsonptr_get(b->echo, ptr);
    if (!json_is_number(v))
        return rd_error_set(err, RD_EREQUEST, path,
                            "%s = \"%s\" names %s in the %s scene (defaults filled), not a "
                            "number",
                            path, ptr,
                            !v                  ? "nothing"
                            : json_is_string(v) ? "a string"
                            : json_is_object(v) ? "an object"
                            : json_is_array(v)  ? "an array"
                                                : "a boolean or null",
                            b->an->name);
    *value = json_number_value(v);
    return RD_OK;
}

/* Writes v (stolen) at ptr in the scene; a container the base as given
 * lacks on the way (the ring pack's default "rings") is first copied from
 * its echo, so that "/rings/2/leak_area_m2" names the default third ring. */
static int write_at(const rd_study_base *b, json_t *scene, const char *ptr, json_t *v)
{
    char prefix[RD_ERROR_PATH_MAX];
    for (const char *slash = strchr(ptr + 1, '/'); v && slash; slash = strchr(slash + 1, '/')) {
        size_t n = (size_t)(slash - ptr);
        if (n >= sizeof prefix)
            break;
        memcpy(prefix, ptr, n);
        prefix[n] = '\0';
        if (rd_jsonptr_get(scene, prefix))
            continue;
        json_t *from = rd_jsonptr_get(b->echo, prefix);
        if (from && rd_jsonptr_set(scene, prefix, json_deep_copy(from)) == -2) {
            json_decref(v);
            return -2;
        }
        break;
    }
    return rd_jsonptr_set(scene, ptr, v);
}

int rd_study_scene(const rd_study_base *b, json_t *set, const char *const *ptrs,
                   const double *values, size_t n, json_t **scene, rd_error *err)
{
    *scene = json_deep_copy(b->scene);
    int rc = *scene ? RD_OK : RD_ENOMEM;
    const char *key;
    json_t *v;
    json_object_foreach(set, key, v)
    {
        if (rc != RD_OK)
            break;
        int st = write_at(b, *scene, key, json_deep_copy(v));
        if (st == -2)
            rc = RD_ENOMEM;
        else if (st != 0)
            rc =
                rd_error_set(err, RD_EREQUEST, "", "%s cannot be written into the base scene", key);
    }
    for (size_t k = 0; k < n && rc == RD_OK; k++) {
        json_t *x = json_real(values[k]);
        if (!x) {
            rc = rd_error_set(err, RD_EREQUEST, "", "%s = %g is not a finite number", ptrs[k],
                              values[k]);
            break;
        }
        int s = write_at(b, *scene, ptrs[k], x);
        if (s == -2)
            rc = RD_ENOMEM;
        else if (s != 0)
            rc = rd_error_set(err, RD_EREQUEST, "", "%s cannot be written into the base scene",
                              ptrs[k]);
    }
    if (rc == RD_ENOMEM)
        rd_error_set(err, RD_ENOMEM, "", "out of memory for a scene of the study");
    if (rc != RD_OK) {
        json_decref(*scene);
        *scene = NULL;
    }
    return rc;
}

int rd_study_try(const rd_study_base *b, json_t *set, const char *const *ptrs, const double *values,
                 size_t n, const char *path, const char *what, rd_error *err)
{
    json_t *scene = NULL;
    rd_error e;
    rd_error_init(&e);
    int rc = rd_study_scene(b, set, ptrs, values, n, &scene, &e);
    rd_scene *sc = NULL;
    if (rc == RD_OK)
        rc = b->ops->parse_value(scene, &sc, &e);
    if (sc)
        b->ops->free(sc);
    json_decref(scene);
    if (rc == RD_OK)
        return RD_OK;
    if (rc == RD_ENOMEM)
        return rd_error_set(err, RD_ENOMEM, path, "out of memory while checking %s", path);
    return rd_error_set(err, RD_EREQUEST, path, "%s makes the base an invalid scene: %s%s%s", what,
                        e.path[0] ? e.path : "", e.path[0] ? ": " : "", e.message);
}

int rd_study_check_observe(const rd_study_base *b, const char *ptr, const char *path, rd_error *err)
{
    if (!ptr || ptr[0] != '/' || !rd_jsonptr_valid(ptr))
        return rd_error_set(err, RD_EREQUEST, path,
                            "%s must be a JSON Pointer into the result (\"/blowby/l_per_min\")",
                            path);
    return rd_result_pointer_check(b->an->name, ptr, path, err);
}

static void collect(json_t *v, double *out, size_t max, size_t *n, int *bad)
{
    if (json_is_number(v)) {
        if (*n < max)
            out[*n] = json_number_value(v);
        (*n)++;
    } else if (json_is_array(v)) {
        for (size_t k = 0; k < json_array_size(v); k++)
            collect(json_array_get(v, k), out, max, n, bad);
    } else {
        *bad = 1;
    }
}

int rd_study_values(json_t *result, const char *ptr, double *out, size_t max, size_t *n)
{
    json_t *v = rd_jsonptr_get(result, ptr);
    int bad = 0;
    *n = 0;
    if (!v)
        return -1;
    collect(v, out, max, n, &bad);
    return bad || *n == 0 ? -1 : 0;
}

/* ---- the batch on threads ------------------------------------------------ */

typedef struct batch {
    const struct rd_scene_ops *ops; /* the base's: how each run is parsed and freed */
    rd_study_run *runs;
    size_t n;
    pthread_mutex_t lock;
    size_t next;     /* the next run to take (under lock) */
    atomic_int stop; /* set when the outer monitor asked to stop */
    const rd_monitor *outer;
    double fraction;
} batch;

/* A helper thread's runs stop when the batch does. */
static int helper_report(void *ctx, double f)
{
    (void)f;
    return atomic_load(&((batch *)ctx)->stop);
}

/* The calling thread's runs also ask the job's monitor (on its own thread). */
static int caller_report(void *ctx, double f)
{
    batch *b = ctx;
    (void)f;
    if (!atomic_load(&b->stop) && b->outer && b->outer->report &&
        b->outer->report(b->outer->ctx, b->fraction))
        atomic_store(&b->stop, 1);
    return atomic_load(&b->stop);
}

static void run_one(const struct rd_scene_ops *ops, rd_study_run *r, const rd_monitor *mon)
{
    rd_scene *sc = NULL;
    rd_error_init(&r->err);
    r->result = NULL;
    r->rc = ops->parse_value(r->scene, &sc, &r->err);
    if (r->rc == RD_OK) {
        r->rc = sc->an->run(sc, mon, &r->result, &r->err);
        if (r->rc == RD_OK && !r->result)
            r->rc = rd_error_set(&r->err, RD_ENOMEM, "", "out of memory for a result");
        if (r->rc != RD_OK) {
            json_decref(r->result);
            r->result = NULL;
        }
    }
    if (sc)
        ops->free(sc);
}

static void work(batch *b, const rd_monitor *mon)
{
    for (;;) {
        pthread_mutex_lock(&b->lock);
        size_t i = b->next < b->n && !atomic_load(&b->stop) ? b->next++ : b->n;
        pthread_mutex_unlock(&b->lock);
        if (i >= b->n)
            return;
        run_one(b->ops, &b->runs[i], mon);
    }
}

static void *helper_main(void *arg)
{
    batch *b = arg;
    rd_monitor mon = {helper_report, b};
    work(b, &mon);
    return NULL;
}

int rd_study_run_batch(const rd_study_base *base, rd_study_run *runs, size_t n, int threads,
                       const rd_monitor *mon, double fraction, rd_error *err)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    size_t t = threads > 0 ? (size_t)threads : cpus > 0 ? (size_t)cpus : 1;
    t = t > RD_STUDY_THREADS_MAX ? RD_STUDY_THREADS_MAX : t;
    t = t > n ? n : t;
    batch b = {.ops = base->ops, .runs = runs, .n = n, .outer = mon, .fraction = fraction};
    pthread_t tid[RD_STUDY_THREADS_MAX];
    size_t started = 0;
    atomic_init(&b.stop, 0);
    if (pthread_mutex_init(&b.lock, NULL) != 0)
        return rd_error_set(err, RD_ENOMEM, "", "cannot create a lock for the study's runs");
    for (size_t k = 1; k < t; k++, started++)
        if (pthread_create(&tid[k - 1], NULL, helper_main, &b) != 0)
            break; /* fewer threads: the calling one still runs everything left */
    rd_monitor own = {caller_report, &b};
    work(&b, &own);
    for (size_t k = 0; k < started; k++)
        pthread_join(tid[k], NULL);
    pthread_mutex_destroy(&b.lock);
    if (atomic_load(&b.stop) || rd_monitor_report(mon, fraction, err) != RD_OK)
        return rd_error_set(err, RD_ECANCELED, "", "the study was cancelled");
    return RD_OK;
}
