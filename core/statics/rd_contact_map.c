/*
 * rd_contact_map — the contact analysis down a bore map (rd_static.h,
 * rd_bore_map.h): one contact solve per layer, each in that layer's bore,
 * with the whole accuracy driver of rd_contact_solve (so each layer's
 * answer is what a contact scene with that bore gives, bit for bit).
 *
 * Cost: the sum of the layers' solves and nothing else; each is as hard as
 * its bore (bench_contact_cost --layers).
 */
#include "rd_bore_map.h"
#include "rd_static.h"

#include <stdio.h>

int rd_contact_solve_layers(const rd_ring_params *p, int segments, const rd_contact_opts *o,
                            const struct rd_bore_map *map, const rd_static_opts *so,
                            const rd_monitor *mon, rd_contact_result *res, rd_error *err)
{
    int n = map->n_layers;
    for (int i = 0; i < n; i++) {
        rd_contact_opts oi = *o;
        oi.bore = map->layer[i].bore;
        rd_monitor_span span;
        const rd_monitor *sub =
            rd_monitor_span_init(&span, mon, (double)i / n, (double)(i + 1) / n);
        rd_error e;
        rd_error_init_local(&e, err);
        int rc = rd_contact_solve(p, segments, &oi, so, sub, &res[i], &e);
        if (rc != RD_OK) {
            char why[RD_ERROR_MESSAGE_MAX];
            snprintf(why, sizeof why, "%s", e.message);
            snprintf(e.message, sizeof e.message,
                     "in the layer at z = %g m (/bore/layers/%d): %.400s", map->layer[i].z, i, why);
            rd_error_forward(err, &e);
            return rc;
        }
    }
    return RD_OK;
}
