#!/usr/bin/env python3
"""A small client of the ringdyn HTTP API (API.md), standard library only.

Submit a scene, wait for the job (a long poll), fetch the result and its CSV
table; a refused scene or a failed job raises RingdynError carrying the
server's JSON error (code, message, and the JSON Pointer `path` of the
field at fault).

As a program:
    python3 ringdyn_client.py [--server URL] [--csv FILE] [--timeout S] scene.json
prints a one-line summary of the result (and writes its CSV table to FILE);
on an error it prints "ringdyn: <path>: <message>" and exits with status 1.

As a module:
    from ringdyn_client import Client, RingdynError
    client = Client("http://127.0.0.1:8080")
    job = client.run({"analysis": "modal", "modal": {"modes": 6}})
    print(job["result"]["modes"][0]["frequency_hz"])
"""

import argparse
import json
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

# A job is live while queued or running; every other status is final (succeeded, failed,
# cancelled, interrupted by a server restart, and any the server adds), so wait() never
# polls a job that cannot change any more.
LIVE = ("queued", "running")


class RingdynError(Exception):
    """An error answer of the server, or a job that did not succeed."""

    def __init__(self, message, code="error", path="", status=None, job=None):
        super().__init__(message)
        self.message = message
        self.code = code
        self.path = path or ""
        self.status = status  # HTTP status, None for a job that failed
        self.job = job  # the finished job, for a failed or cancelled one

    def __str__(self):
        return f"{self.path}: {self.message}" if self.path else self.message


class Client:
    def __init__(self, base="http://127.0.0.1:8080", timeout=30.0):
        self.base = base.rstrip("/")
        self.timeout = timeout  # per request, s

    def _request(self, method, path, body=None, accept="application/json"):
        data = None if body is None else json.dumps(body).encode()
        headers = {"Accept": accept}
        if data is not None:
            headers["Content-Type"] = "application/json"
        req = urllib.request.Request(self.base + path, data=data, method=method, headers=headers)
        try:
            with urllib.request.urlopen(req, timeout=self.timeout) as resp:
                raw = resp.read()
        except urllib.error.HTTPError as e:
            raise _http_error(e) from None
        except urllib.error.URLError as e:
            raise RingdynError(f"cannot reach {self.base}: {e.reason}", code="network") from None
        return raw if accept != "application/json" else json.loads(raw)

    def submit(self, scene, wait=0):
        """POST the scene; the job as the server answers (finished if it ended within `wait` s)."""
        return self._request("POST", f"/api/v1/jobs?wait={wait:g}", scene)

    def job(self, job_id, wait=0):
        """The job; with `wait` > 0 (s, at most 60) the server holds the answer until the job
        ends or that time has passed (a long poll)."""
        query = f"?wait={wait:.3f}" if wait > 0 else ""
        return self._request("GET", "/api/v1/jobs/" + urllib.parse.quote(job_id) + query)

    def cancel(self, job_id):
        return self._request("DELETE", "/api/v1/jobs/" + urllib.parse.quote(job_id))

    def wait(self, job, poll=0.5, timeout=600.0, on_progress=None):
        """Long-polls `job` (a job object or id) until it has finished; returns it. Each
        request waits up to `poll` s on the server, which answers as soon as the job ends;
        on_progress sees the job after each.

        Raises RingdynError if it ended otherwise than succeeded (failed,
        cancelled, interrupted: with .job set and .code the error's code or
        the status), or if it is still live after `timeout` s (the job keeps
        running)."""
        if isinstance(job, str):
            job = self.job(job)
        deadline = time.monotonic() + timeout
        while job["status"] in LIVE:
            if on_progress:
                on_progress(job)
            if time.monotonic() > deadline:
                raise RingdynError(f"job {job['id']} is still {job['status']} after {timeout:g} s", code="timeout")
            hold = min(poll, 60.0, max(deadline - time.monotonic(), 0.0), self.timeout / 2)
            asked = time.monotonic()
            job = self.job(job["id"], wait=hold)
            if job["status"] in LIVE and time.monotonic() - asked < min(hold, 0.1):
                time.sleep(poll)  # not held (a proxy in the way): no tight loop
        if job["status"] != "succeeded":
            err = job.get("error") or {}
            raise RingdynError(err.get("message") or f"job {job['id']} {job['status']}",
                               code=err.get("code", job["status"]), path=err.get("path", ""), job=job)
        return job

    def run(self, scene, **wait_args):
        """Submits `scene` and waits for it: the succeeded job, with its result."""
        return self.wait(self.submit(scene), **wait_args)

    def csv(self, job_id):
        """The main table of a finished job as CSV text."""
        return self._request("GET", f"/api/v1/jobs/{urllib.parse.quote(job_id)}/result.csv",
                             accept="text/csv").decode("utf-8")


def _http_error(e):
    """RingdynError from the server's {"error": {code, message, path}}."""
    try:
        err = json.loads(e.read()).get("error") or {}
    except ValueError:
        err = {}
    message = err.get("message") or f"HTTP {e.code} {e.reason}"
    if e.code == 429 and e.headers.get("Retry-After"):
        message += f" (retry in {e.headers['Retry-After']} s)"
    return RingdynError(message, code=err.get("code", "http"), path=err.get("path", ""), status=e.code)


def summary(result):
    """One line on a result, whatever its analysis."""
    n = result.get("numerics", {})
    a = result.get("analysis")
    if a == "modal":
        what = "first frequencies " + ", ".join(f"{m['frequency_hz']:.1f}" for m in result["modes"][:3]) + " Hz"
    elif a == "pretension":
        what = f"gap opening x_a = {result['gap_opening_inner'] * 1e3:.3f} mm"
    elif a == "contact":
        what = f"mean pressure {result['mean_pressure_pa'] / 1e6:.4g} MPa, contact fraction {result['contact_fraction']:.3f}"
    elif a == "lift":
        what = f"{len(result['crank_deg'])} samples, {len(result.get('events', []))} flank events"
    else:
        what = "result"
    err = n.get("error_estimate")
    return f"{a}: {what}; {n.get('segments')} segments, wall time {n.get('wall_s', 0):.3g} s" + (
        f", estimated error {abs(err) * 100:.2g} %" if isinstance(err, (int, float)) else "")


def main(argv=None):
    ap = argparse.ArgumentParser(description="Run a ringdyn scene on a server and print the result.")
    ap.add_argument("scene", help="scene JSON file (API.md), e.g. examples/thesis_modal.json")
    ap.add_argument("--server", default="http://127.0.0.1:8080", help="base URL of ringdyn-server")
    ap.add_argument("--csv", metavar="FILE", help="also write the result's CSV table here")
    ap.add_argument("--timeout", type=float, default=600.0, help="give up waiting after this many s")
    args = ap.parse_args(argv)
    try:
        with open(args.scene, encoding="utf-8") as f:
            scene = json.load(f)
        client = Client(args.server)
        job = client.run(scene, timeout=args.timeout,
                         on_progress=lambda j: print(f"job {j['id']} {j['status']} {j.get('progress', 0) * 100:.0f} %",
                                                     file=sys.stderr))
        print(f"job {job['id']} succeeded: {summary(job['result'])}")
        if args.csv:
            with open(args.csv, "w", encoding="utf-8") as f:
                f.write(client.csv(job["id"]))
    except RingdynError as e:
        print(f"ringdyn: {e}", file=sys.stderr)
        return 1
    except (OSError, ValueError) as e:
        print(f"ringdyn: {args.scene}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
