"""The requests of contract.py, one group a function: each answer goes
through call(name, method, path, body, headers, ctype), which validates it
against the served document and returns (status, headers, parsed JSON)."""
import json
import time

REPORT = {}  # ok(name), bad(name, why): contract.py's counters
MODAL = '{"analysis":"modal"}'
SLOW = '{"analysis":"modal","discretization":{"segments":2000},"modal":{"modes":60}}'


def examples(call):
    """Every shipped example, as served, run to its end through the API."""
    st, _, body = call("GET /api/v1/examples", "GET", "/api/v1/examples")
    names = [e["name"] for e in (body or {}).get("examples", [])]
    ids = []
    for name in names:
        st, _, scene = call("GET /api/v1/examples/" + name, "GET", "/api/v1/examples/" + name)
        if scene is None:
            continue
        st, _, job = call("example %s through POST /api/v1/jobs?wait=280" % name, "POST",
                          "/api/v1/jobs?wait=280", json.dumps(scene),
                          {"Cache-Control": "no-cache"})
        if job and job.get("id"):
            ids.append(job["id"])
            if job.get("status") != "succeeded":
                REPORT["bad"]("example %s succeeds" % name, "%s: %s" % (
                    job.get("status"), json.dumps(job.get("error"))))
    return names, ids


def jobs(call, ids):
    """Job lists (filters, pages), one job, its CSV, ETags, long poll, DELETE."""
    call("GET /api/v1/jobs", "GET", "/api/v1/jobs")
    for a in ("modal", "pretension", "contact", "lift", "ringpack"):
        call("GET /api/v1/jobs?analysis=" + a, "GET", "/api/v1/jobs?analysis=" + a)
    call("GET /api/v1/jobs?status=succeeded&limit=2", "GET", "/api/v1/jobs?status=succeeded&limit=2")
    st, _, page = call("GET /api/v1/jobs?limit=1", "GET", "/api/v1/jobs?limit=1")
    if page and page.get("next_cursor"):
        call("GET /api/v1/jobs?cursor=...", "GET", "/api/v1/jobs?limit=1&cursor=" + page["next_cursor"])
    if not ids:
        return
    st, h, job = call("GET /api/v1/jobs/{id}", "GET", "/api/v1/jobs/" + ids[0])
    etag = h.get("ETag")
    if etag:
        call("GET /api/v1/jobs/{id} If-None-Match", "GET", "/api/v1/jobs/" + ids[0],
             headers={"If-None-Match": etag})
    call("GET /api/v1/jobs/{id}?wait=1 (finished)", "GET", "/api/v1/jobs/%s?wait=1" % ids[0])
    st, h, _ = call("GET result.csv", "GET", "/api/v1/jobs/%s/result.csv" % ids[0])
    if h.get("ETag"):
        call("GET result.csv If-None-Match", "GET", "/api/v1/jobs/%s/result.csv" % ids[0],
             headers={"If-None-Match": h.get("ETag")})
    # a running job: 202, its poll, a cancel (200 + the job), then a delete of
    # the finished one (204), then 404
    st, _, run = call("POST a slow job (202)", "POST", "/api/v1/jobs", SLOW,
                      {"Cache-Control": "no-cache"})
    if run and run.get("id"):
        jid = run["id"]
        call("GET a queued or running job", "GET", "/api/v1/jobs/" + jid)
        call("GET ?wait=0.2 of a running job", "GET", "/api/v1/jobs/%s?wait=0.2" % jid)
        call("DELETE a running job (cancel)", "DELETE", "/api/v1/jobs/" + jid)
        for _ in range(100):
            st, _, j = call("GET the cancelled job", "GET", "/api/v1/jobs/" + jid)
            if j and j.get("status") not in ("queued", "running"):
                break
            time.sleep(0.1)
        call("GET result.csv of a cancelled job", "GET", "/api/v1/jobs/%s/result.csv" % jid)
        call("DELETE a finished job", "DELETE", "/api/v1/jobs/" + jid)
        call("GET a deleted job", "GET", "/api/v1/jobs/" + jid)
    # the result cache: the same scene again answers the earlier job (cached)
    call("POST modal", "POST", "/api/v1/jobs?wait=60", MODAL)
    call("POST modal again (the cache)", "POST", "/api/v1/jobs?wait=60", MODAL)
    # a failed job: an error object, no result
    st, _, f = call("POST a lift with a tiny time limit", "POST",
                    "/api/v1/jobs?wait=60&time_limit_s=0.001",
                    '{"analysis":"lift","engine":{"cycles":4}}', {"Cache-Control": "no-cache"})


def sweeps(call):
    spec = ('{"base": {"analysis": "modal", "modal": {"modes": 3}}, "parameters": '
            '[{"path": "/ring/closed_gap", "values": [1e-4, 3e-4]}], '
            '"outputs": ["/modes/0/frequency_hz", "count(/modes)"]}')
    st, _, sw = call("POST a sweep ?wait", "POST", "/api/v1/sweeps?wait=60", spec)
    st, _, sw2 = call("POST a sweep (202)", "POST", "/api/v1/sweeps",
                      spec.replace("3e-4", "4e-4"))
    call("POST a fidelity sweep", "POST", "/api/v1/sweeps?wait=60",
         '{"fidelity": {"analysis": "modal", "modal": {"modes": 3}}, "segments": [5, 10, 20]}')
    call("GET /api/v1/sweeps", "GET", "/api/v1/sweeps")
    if sw and sw.get("id"):
        call("GET /api/v1/sweeps/{id}", "GET", "/api/v1/sweeps/" + sw["id"])
        call("GET table.csv", "GET", "/api/v1/sweeps/%s/table.csv" % sw["id"])
        call("DELETE a finished sweep", "DELETE", "/api/v1/sweeps/" + sw["id"])
        call("GET a deleted sweep", "GET", "/api/v1/sweeps/" + sw["id"])
    slow = ('{"base": %s, "parameters": [{"path": "/ring/tangential_force", '
            '"values": [5, 6, 7, 8]}], "outputs": ["/modes/0/frequency_hz"]}' % SLOW)
    st, _, s3 = call("POST a slow sweep", "POST", "/api/v1/sweeps", slow)
    if s3 and s3.get("id"):
        call("DELETE a running sweep (cancel)", "DELETE", "/api/v1/sweeps/" + s3["id"])
    call("POST a sweep: misspelt output", "POST", "/api/v1/sweeps",
         spec.replace("/modes/0/frequency_hz", "/modes/0/frequency"))
    call("POST a sweep: not JSON", "POST", "/api/v1/sweeps", "{")
    call("POST a sweep: text/plain", "POST", "/api/v1/sweeps", spec, ctype="text/plain")
    call("GET an unknown sweep", "GET", "/api/v1/sweeps/0123456789abcdef")
    call("GET the table of an unknown sweep", "GET", "/api/v1/sweeps/0123456789abcdef/table.csv")
    call("PUT /api/v1/sweeps", "PUT", "/api/v1/sweeps", spec)


def errors(call):
    """Every error a client can provoke on one loopback server."""
    post = lambda name, body, path="/api/v1/jobs", **kw: call(name, "POST", path, body, **kw)
    post("not JSON", "{")
    post("a JSON array", "[1]")
    post("an unknown analysis", '{"analysis":"modl"}')
    post("a misspelt field", '{"analysis":"modal","ring":{"diamter":0.08}}')
    post("a block the analysis does not read", '{"analysis":"modal","engine":{"speed_rpm":900}}')
    post("an unphysical value", '{"analysis":"modal","ring":{"radial_width":-1}}')
    post("over a size limit", '{"analysis":"modal","discretization":{"segments":100000}}')
    post("many problems", '{"analysis":"lift","ring":{"diameter":"x","radial_width":-1},'
         '"engine":{"speed_rpm":0,"cycles":1e9},"groove":{"axial_clearance":-1}}')
    post("text/plain", MODAL, ctype="text/plain")
    post("too large (Content-Length 2 MiB)", 2 << 20)
    post("a sweep too large", 2 << 20, "/api/v1/sweeps")
    post("a bad query parameter", MODAL, "/api/v1/jobs?wait=abc")
    post("an unknown query parameter", MODAL, "/api/v1/jobs?colour=red")
    call("a bad list filter", "GET", "/api/v1/jobs?status=done")
    call("a bad cursor", "GET", "/api/v1/jobs?cursor=zzz")
    call("an unknown job", "GET", "/api/v1/jobs/0123456789abcdef")
    call("a malformed job id", "GET", "/api/v1/jobs/xyz")
    call("the CSV of an unknown job", "GET", "/api/v1/jobs/0123456789abcdef/result.csv")
    call("DELETE an unknown job", "DELETE", "/api/v1/jobs/0123456789abcdef")
    call("DELETE a job, an unknown query parameter", "DELETE",
         "/api/v1/jobs/0123456789abcdef?colour=red")
    call("DELETE an unknown sweep", "DELETE", "/api/v1/sweeps/0123456789abcdef")
    call("DELETE a sweep, an unknown query parameter", "DELETE",
         "/api/v1/sweeps/0123456789abcdef?colour=red")
    call("an unknown example", "GET", "/api/v1/examples/nope")
    call("PUT /api/v1/jobs", "PUT", "/api/v1/jobs", MODAL)
    call("POST /api/v1/health", "POST", "/api/v1/health", "{}")
    call("DELETE /api/v1/examples", "DELETE", "/api/v1/examples")
    call("POST /api/v1/openapi.json", "POST", "/api/v1/openapi.json", "{}")
    call("POST /metrics", "POST", "/metrics", "{}")
    # Idempotency-Key: replay, then the same key with another body
    key = {"Idempotency-Key": "contract-1", "Cache-Control": "no-cache"}
    post("Idempotency-Key, first", '{"analysis":"modal","discretization":{"segments":9}}',
         "/api/v1/jobs?wait=60", headers=key)
    post("Idempotency-Key, replay", '{"analysis":"modal","discretization":{"segments":9}}',
         "/api/v1/jobs?wait=60", headers=key)
    post("Idempotency-Key, another body", '{"analysis":"modal","discretization":{"segments":10}}',
         headers=key)
    post("an empty Idempotency-Key", MODAL, headers={"Idempotency-Key": ""})


GETS = ["/api/v1/health", "/api/v1/examples", "/api/v1/examples/thesis_modal",
        "/api/v1/openapi.json", "/metrics", "/api/v1/jobs", "/api/v1/jobs/0123456789abcdef",
        "/api/v1/jobs/0123456789abcdef/result.csv", "/api/v1/sweeps",
        "/api/v1/sweeps/0123456789abcdef", "/api/v1/sweeps/0123456789abcdef/table.csv"]


def others(call):
    call("GET /api/v1/health", "GET", "/api/v1/health")
    call("GET /api/v1/openapi.json", "GET", "/api/v1/openapi.json")
    call("GET /metrics", "GET", "/metrics")
    call("GET /", "GET", "/")
    call("GET /static/app.js", "GET", "/static/app.js")
    call("GET /static/style.css", "GET", "/static/style.css")
    call("GET /docs", "GET", "/docs")
    call("a file not there", "GET", "/static/nothing.js")
    call("an unknown path", "GET", "/api/v1/nothing")
    for path in GETS:  # every path: an unknown query parameter (400), a method it has not (405)
        call("GET %s?colour=red" % path, "GET", path + "?colour=red")
    for path in GETS + ["/", "/docs", "/static/app.js"]:
        call("PATCH " + path, "PATCH", path, "{}")


def queue_full(call, base_b):
    """One worker, a queue of one: the third slow job is refused (429). The
    second is posted once the worker has taken the first (on a loaded machine
    the worker may not have run yet, and the second would find the queue full)."""
    for i in range(3):
        st, h, job = call("POST a slow job to the one-worker server (%d)" % (i + 1), "POST",
                          "/api/v1/jobs", SLOW.replace("60}", "%d}" % (60 - i)), on=base_b)
        for _ in range(600 if i == 0 and job and job.get("id") else 0):
            _, _, j = call("GET the first slow job", "GET", "/api/v1/jobs/" + job["id"],
                           on=base_b)
            if not j or j.get("status") != "queued":
                break
            time.sleep(0.05)
    if st == 429 and h.get("Retry-After"):
        REPORT["ok"]("the third slow job -> 429 with Retry-After")
    else:
        REPORT["bad"]("the third slow job -> 429 with Retry-After", "got %s" % st)


def cases(call, base_b, ok, bad):
    REPORT.update(ok=ok, bad=bad)
    names, ids = examples(call)
    print("note - %d examples run: %s" % (len(names), ", ".join(names)))
    jobs(call, ids)
    sweeps(call)
    errors(call)
    others(call)
    queue_full(call, base_b)
