/*
 * rd_registry — the list of analyses, and the walks over a list that
 * parsing and the OpenAPI document share (rd_registry.h).  The OpenAPI
 * scene schemas written from a list are in rd_openapi.c.
 *
 * To add an analysis: write api/rd_an_<name>.c (copy the shape of
 * rd_an_contact.c), declare it below and add it to rd_registry[].
 */
#include "rd_registry.h"

#include <string.h>

extern const rd_analysis_def rd_an_modal;
extern const rd_analysis_def rd_an_pretension;
extern const rd_analysis_def rd_an_contact;
extern const rd_analysis_def rd_an_lift;
extern const rd_analysis_def rd_an_ringpack;
extern const rd_analysis_def rd_an_calibration;
extern const rd_analysis_def rd_an_sensitivity;

/* In enum rd_analysis order; a new analysis goes at the end. */
const rd_analysis_def *const rd_registry[] = {
    &rd_an_modal,    &rd_an_pretension,  &rd_an_contact,     &rd_an_lift,
    &rd_an_ringpack, &rd_an_calibration, &rd_an_sensitivity, NULL,
};

const rd_analysis_def *rd_registry_find(const rd_analysis_def *const *registry, const char *name,
                                        int *index)
{
    for (int i = 0; registry[i]; i++)
        if (strcmp(registry[i]->name, name) == 0) {
            if (index)
                *index = i;
            return registry[i];
        }
    return NULL;
}

static int reads_key(const rd_analysis_def *an, const char *key)
{
    for (const rd_field *f = an->scene->fields; f->key; f++)
        if (strcmp(f->key, key) == 0)
            return 1;
    return 0;
}

static int listed(const char *const *keys, int n, const char *key)
{
    for (int i = 0; i < n; i++)
        if (strcmp(keys[i], key) == 0)
            return 1;
    return 0;
}

int rd_registry_ignored(const rd_analysis_def *const *registry, const rd_analysis_def *an,
                        const char **keys, int max)
{
    /* The contract's order (refusals are reported in the scene's); keys of
     * later analyses follow in registry order. */
    static const char *const contract[] = {"modal",   "pretension", "bore",     "engine",  "groove",
                                           "physics", "output",     "numerics", "contact", NULL};
    int n = 0;
    for (int i = 0; contract[i] && n < max - 1; i++) {
        int read_elsewhere = 0;
        for (int a = 0; registry[a]; a++)
            read_elsewhere |= registry[a] != an && reads_key(registry[a], contract[i]);
        if (read_elsewhere && !reads_key(an, contract[i]))
            keys[n++] = contract[i];
    }
    for (int a = 0; registry[a]; a++)
        for (const rd_field *f = registry[a]->scene->fields; f->key && n < max - 1; f++)
            if (registry[a] != an && !reads_key(an, f->key) && !listed(keys, n, f->key))
                keys[n++] = f->key;
    keys[n] = NULL;
    return n;
}
