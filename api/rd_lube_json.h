/*
 * rd_lube_json.h — the lubrication block of a result (the lift analysis'
 * and each ring of the ring pack's), from core's rd_lift_lube.
 */
#ifndef RD_LUBE_JSON_H
#define RD_LUBE_JSON_H

#include "rd_lift.h"

struct json_t;

/* The block of N samples, its `method` text given; NULL on out of memory. */
struct json_t *rd_result_lube(const rd_lift_lube *lb, int N, const char *method);

#endif
