/*
 * test_sweep_request — the body of POST /api/v1/sweeps (api/rd_sweep_request.h):
 * a spec and a fidelity request give the sweeps rd_sweep_parse and
 * rd_sweep_fidelity_spec give (same hash, same points); the errors of a
 * fidelity request point into the request, not into the generated spec; the
 * row of a stopped point carries the same parameter values as the row
 * rd_sweep_run_point writes for that point (read back from the point's scene,
 * a second path), null outputs, and the stop's code and message.
 */
#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "rd_sweep_request.h"

static int parse(const char *body, rd_sweep_request *req, rd_error *err)
{
    rd_error_init(err);
    return rd_sweep_request_parse(body, strlen(body), 1000, req, err);
}

static void test_spec(void)
{
    const char *spec =
        "{\"base\": {\"analysis\": \"modal\", \"discretization\": {\"segments\": 10}},"
        " \"parameters\": [{\"path\": \"/ring/radial_width\", \"values\": [0.0025, 0.003]},"
        " {\"path\": \"/ring/tangential_force\", \"range\": {\"start\": 8, \"stop\": 12, "
        "\"count\": 3}}], \"outputs\": [\"/modes/0/frequency_hz\"]}";
    rd_sweep_request req;
    rd_error err;
    CHECK(parse(spec, &req, &err) == RD_OK, "a spec parses: %s", err.message);
    CHECK(!req.fidelity && req.n_params == 2, "a spec: not fidelity, 2 parameters");
    CHECK(req.sweep && rd_sweep_points(req.sweep) == 6, "2 x 3 points");
    rd_sweep *direct = NULL;
    rd_error_init(&err);
    rd_sweep_parse(spec, strlen(spec), 1000, &direct, &err);
    CHECK(direct && strcmp(rd_sweep_hash(direct), rd_sweep_hash(req.sweep)) == 0,
          "the same sweep as rd_sweep_parse");
    rd_sweep_free(direct);

    /* The failed row of point 4 against the row rd_sweep_run_point writes. */
    char *ran = NULL;
    rd_error_init(&err);
    CHECK(rd_sweep_run_point(req.sweep, 4, NULL, &ran, &err) == RD_OK && ran, "point 4 runs");
    rd_error why;
    rd_error_init(&why);
    rd_error_set(&why, RD_ETIMEOUT, "", "Point 4 ran longer than 0.5 s.");
    char *failed = rd_sweep_request_failed_row(&req, 4, &why, &err);
    json_t *a = ran ? json_loads(ran, 0, NULL) : NULL,
           *b = failed ? json_loads(failed, 0, NULL) : NULL;
    CHECK(json_array_size(a) == 5 && json_array_size(b) == 5, "both rows have the 5 columns");
    CHECK(json_equal(json_array_get(a, 0), json_array_get(b, 0)) &&
              json_equal(json_array_get(a, 1), json_array_get(b, 1)),
          "the parameter values match the run's: %s vs %s", ran ? ran : "-", failed ? failed : "-");
    CHECK(json_is_null(json_array_get(b, 2)), "the output is null");
    CHECK(strcmp(json_string_value(json_array_get(b, 3)) ? json_string_value(json_array_get(b, 3))
                                                         : "",
                 "time_limit") == 0,
          "status time_limit");
    CHECK(strcmp(json_string_value(json_array_get(b, 4)) ? json_string_value(json_array_get(b, 4))
                                                         : "",
                 "Point 4 ran longer than 0.5 s.") == 0,
          "the message");
    rd_error_init(&err);
    CHECK(rd_sweep_request_failed_row(&req, 6, &why, &err) == NULL && err.code == RD_EINVAL,
          "point 6 of 6 does not exist");
    json_decref(a);
    json_decref(b);
    free(ran);
    free(failed);
    rd_sweep_request_cleanup(&req);
    rd_sweep_request_cleanup(&req); /* twice: no-op */
}

static void test_fidelity(void)
{
    rd_sweep_request req;
    rd_error err;
    const char *scene = "{\"analysis\": \"modal\"}";
    CHECK(parse("{\"fidelity\": {\"analysis\": \"modal\"}}", &req, &err) == RD_OK, "fidelity: %s",
          err.message);
    char *spec = rd_sweep_fidelity_spec(scene, strlen(scene), NULL, &err);
    rd_sweep *direct = NULL;
    if (spec)
        rd_sweep_parse(spec, strlen(spec), 1000, &direct, &err);
    CHECK(req.fidelity && req.n_params == 1, "fidelity, one parameter (segments)");
    CHECK(direct && req.sweep && strcmp(rd_sweep_hash(direct), rd_sweep_hash(req.sweep)) == 0 &&
              rd_sweep_points(req.sweep) == 7,
          "the sweep of rd_sweep_fidelity_spec (the CLI's), 7 segment counts");
    rd_sweep_free(direct);
    free(spec);
    rd_sweep_request_cleanup(&req);

    CHECK(parse("{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": [5, 10, 20]}", &req,
                &err) == RD_OK &&
              rd_sweep_points(req.sweep) == 3,
          "segments replace the ladder");
    rd_sweep_request_cleanup(&req);
    CHECK(parse("{\"fidelity\": {\"analysis\": \"lift\", \"engine\": {\"cycles\": 0.05}}, "
                "\"segments\": [4, 8], \"rtol\": [1e-4, 1e-5, 1e-6]}",
                &req, &err) == RD_OK &&
              req.n_params == 2 && rd_sweep_points(req.sweep) == 6,
          "lift: segments x rtol: %s", err.message);
    rd_sweep_request_cleanup(&req);
}

/* Each bad request: its status and the path into the request. */
static void test_errors(void)
{
    static const struct {
        const char *body, *path;
        int code;
    } cases[] = {
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": [5, 2]}", "/segments/1",
         RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"lift\"}, \"rtol\": [1e-4, 0.5]}", "/rtol/1", RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"models\": [\"x\"]}", "/models/0",
         RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\", \"ring\": {\"diameter\": -1}}}",
         "/fidelity/ring/diameter", RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"segmnts\": [5]}", "/segmnts", RD_EREQUEST},
        {"{\"fidelity\": 3}", "/fidelity", RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": 5}", "/segments", RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": [\"a\"]}", "/segments/0",
         RD_EREQUEST},
        {"{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": []}", "/segments", RD_EREQUEST},
        {"{\"base\": {\"analysis\": \"modal\"}, \"parameters\": [{\"path\": "
         "\"/ring/tangential_force\","
         " \"values\": []}], \"outputs\": [\"/modes/0/frequency_hz\"]}",
         "/parameters/0/values", RD_EREQUEST},
        {"{\"base\": ", "", RD_EJSON},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rd_sweep_request req;
        rd_error err;
        int rc = parse(cases[k].body, &req, &err);
        CHECK(rc == cases[k].code && strcmp(err.path, cases[k].path) == 0 && err.message[0] &&
                  !req.sweep,
              "case %zu: got %d at '%s' (%s), want %d at '%s'", k, rc, err.path, err.message,
              cases[k].code, cases[k].path);
    }
    /* 65 segment counts: over the list limit. */
    char body[1024] = "{\"fidelity\": {\"analysis\": \"modal\"}, \"segments\": [5";
    for (int k = 1; k < RD_SWEEP_REQUEST_LIST_MAX + 1; k++)
        strcat(body, ", 5");
    strcat(body, "]}");
    rd_sweep_request req;
    rd_error err;
    CHECK(parse(body, &req, &err) == RD_EREQUEST && strcmp(err.path, "/segments") == 0,
          "65 entries are refused");
}

int main(void)
{
    test_spec();
    test_fidelity();
    test_errors();
    return check_done();
}
