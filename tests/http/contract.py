#!/usr/bin/env python3
"""The served OpenAPI document against real answers of a live server.

    contract.py SERVER EXAMPLES_DIR

Starts SERVER on 127.0.0.1 (--port 0, an in-memory store), reads
/api/v1/openapi.json from it, then sends every shipped example (as served by
/api/v1/examples) through POST /api/v1/jobs?wait=, a sweep and a fidelity
sweep, job and sweep lists, and every error the API can answer with that a
client can provoke on one server (400, 404, 405, 409, 413, 415, 422, 304,
204). Each answer is matched to its operation and status in the document and
its body validated against the schema there, with python3-jsonschema
(Debian's package; Draft 4, the dialect OpenAPI 3.0's Schema Object extends,
with `nullable` written as a null type).

Strict: the test closes every object schema that does not say otherwise
(additionalProperties false), so a member the server sends and the document
does not describe fails here, while the served document stays open (clients
ignore unknown keys). A status the operation does not list, a content type it
does not list, or an answer kind the document describes for an operation the
test did not produce is reported; the last line gives the coverage.
"""
import copy
import gzip
import json
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

try:
    import jsonschema
except ImportError:
    print("contract FAILED: python3-jsonschema is missing; install it with "
          "scripts/install-deps.sh --test", file=sys.stderr)
    sys.exit(1)

PASSED = 0
FAILED = 0


QUIET = False  # --answers: only the failures and the summary


def ok(name):
    global PASSED
    PASSED += 1
    if not QUIET:
        print("ok   - " + name)


def bad(name, why=""):
    global FAILED
    FAILED += 1
    print("FAIL - " + name + (" (" + why + ")" if why else ""))


# ---- OpenAPI 3.0 Schema Object -> JSON Schema Draft 4 ------------------------
def to_draft4(node, strict):
    """A copy of an OpenAPI 3.0 schema tree as Draft 4: `nullable` folded into
    the type (and the enum), OpenAPI-only keywords dropped; with `strict`,
    object schemas with properties and no additionalProperties closed."""
    if isinstance(node, list):
        return [to_draft4(x, strict) for x in node]
    if not isinstance(node, dict):
        return node
    out = {}
    for k, v in node.items():
        if k in ("discriminator", "example", "xml", "externalDocs", "deprecated",
                 "readOnly", "writeOnly", "nullable"):
            continue
        if k in ("properties", "patternProperties"):
            out[k] = {p: to_draft4(s, strict) for p, s in v.items()}
        else:
            out[k] = to_draft4(v, strict)
    if node.get("nullable") is True:
        if "type" in out:
            t = out["type"]
            out["type"] = (t if isinstance(t, list) else [t]) + ["null"]
        if "enum" in out and None not in out["enum"]:
            out["enum"] = out["enum"] + [None]
        if "$ref" in out:  # a $ref's siblings are ignored in Draft 4
            out = {"anyOf": [{"$ref": out.pop("$ref")}, {"type": "null"}], **out}
    if (strict and "properties" in out and "additionalProperties" not in out
            and not any(k in out for k in ("$ref", "oneOf", "anyOf", "allOf"))):
        out["additionalProperties"] = False
    return out


class Contract:
    def __init__(self, doc):
        self.doc = doc
        comps = doc["components"]
        self.root = {"components": {"schemas": to_draft4(comps["schemas"], True)}}
        self.open_allof(self.root["components"]["schemas"])
        self.responses = comps.get("responses", {})
        self.ops = []  # (method, regex, template, operation)
        for tmpl, item in doc["paths"].items():
            rx = "^" + re.sub(r"\\\{[^}]+\\\}", "[^/]+", re.escape(tmpl)) + "$"
            if tmpl == "/static/{path}":
                rx = "^/static/.+$"
            for method, op in item.items():
                if method in ("get", "post", "put", "delete", "patch", "head"):
                    self.ops.append((method.upper(), re.compile(rx), tmpl, op))
        self.seen = set()
        self.answers = 0
        self.cache = {}

    def open_allof(self, node):
        """An allOf's members are each closed by to_draft4; they must accept
        each other's keys: each member gets the union of the members'
        properties (as empty schemas where it has none of its own)."""
        if isinstance(node, list):
            for x in node:
                self.open_allof(x)
            return
        if not isinstance(node, dict):
            return
        for v in node.values():
            self.open_allof(v)
        if "allOf" in node:
            names = set()
            for m in node["allOf"]:
                names |= set(self.props(m))
            for m in node["allOf"]:
                if m.get("additionalProperties") is False:
                    for n in names:
                        m["properties"].setdefault(n, {})
                elif "$ref" in m:
                    # the referenced schema is closed: replace the member by
                    # an open copy and close the whole allOf instead
                    target = self.resolve(m["$ref"])
                    m.pop("$ref")
                    m.update(copy.deepcopy(target))
                    if m.get("additionalProperties") is False:
                        for n in names:
                            m["properties"].setdefault(n, {})

    def resolve(self, ref):
        node = self.root
        for part in ref.lstrip("#/").split("/"):
            node = node[part.replace("~1", "/").replace("~0", "~")]
        return node

    def props(self, schema):
        if "$ref" in schema:
            schema = self.resolve(schema["$ref"])
        names = set(schema.get("properties", {}))
        for m in schema.get("allOf", []):
            names |= self.props(m)
        return names

    def find(self, method, path):
        """The operation of METHOD on PATH; a path the document has with
        other methods only: its 405 answer."""
        path = path.split("?", 1)[0]
        for m, rx, tmpl, op in self.ops:
            if m == method and rx.match(path):
                return tmpl, op
        for m, rx, tmpl, op in self.ops:
            if rx.match(path) and "405" in op["responses"]:
                self.seen.add((m, tmpl, "405"))
                return tmpl, {"responses": {"405": op["responses"]["405"]}}
        return None, None

    def validator(self, schema):
        key = json.dumps(schema, sort_keys=True)
        if key not in self.cache:
            root = dict(self.root)
            root.update(to_draft4(schema, True))
            self.cache[key] = jsonschema.Draft4Validator(root, format_checker=FORMATS)
        return self.cache[key]

    def check(self, name, method, path, status, ctype, body):
        """Validates one answer; returns the parsed JSON body (or None)."""
        self.answers += 1
        tmpl, op = self.find(method, path)
        if op is None and status == 404:  # an unknown path: the NotFound answer
            tmpl, op = "(unknown path)", {"responses": {"404": {"$ref": "NotFound"}}}
        if op is None:
            bad(name, "%s %s is not in the document" % (method, path))
            return None
        resp = op["responses"].get(str(status)) or op["responses"].get("default")
        if resp is None:
            bad(name, "%s %s answered %s, which the document does not list (%s)" %
                (method, tmpl, status, ", ".join(op["responses"])))
            return None
        if "$ref" in resp:
            resp = self.responses[resp["$ref"].split("/")[-1]]
        self.seen.add((method, tmpl, str(status)))
        content = resp.get("content")
        if not content:
            if body:
                bad(name, "%s %s %s: the document says no body, got %d bytes" %
                    (method, tmpl, status, len(body)))
            else:
                ok(name + " -> %s, no body, as documented" % status)
            return None
        mt = (ctype or "").split(";")[0].strip()
        media = content.get(mt)
        if media is None and (mt.split("/")[0] + "/*" in content or "*/*" in content):
            ok(name + " -> %s %s, a type the document allows" % (status, mt))  # (any file)
            return None
        if media is None:
            bad(name, "%s %s %s: content type %r not in the document (%s)" %
                (method, tmpl, status, mt, ", ".join(content)))
            return None
        if mt != "application/json":
            ok(name + " -> %s %s, as documented" % (status, mt))
            return None
        try:
            value = json.loads(body)
        except ValueError as e:
            bad(name, "not JSON: %s" % e)
            return None
        schema = media.get("schema")
        if schema is None:
            bad(name, "%s %s %s: no schema" % (method, tmpl, status))
            return value
        errors = sorted(leaves(self.validator(schema).iter_errors(value)),
                        key=lambda e: list(e.path))
        if errors:
            why = "; ".join("/%s: %s" % ("/".join(str(p) for p in e.absolute_path),
                                         e.message[:300]) for e in errors[:8])
            bad(name + " -> %s valid against %s %s" % (status, tmpl, status), why)
        else:
            ok(name + " -> %s valid against the document" % status)
        return value

    def documented(self):
        kinds = set()
        for m, _, tmpl, op in self.ops:
            for st in op["responses"]:
                kinds.add((m, tmpl, st))
        return kinds


def leaves(errors):
    """The errors to report: a oneOf's (the Result, the Scene) are those of
    the branch its discriminator picks, the one whose `analysis` matched."""
    out = []
    for e in errors:
        if e.validator != "oneOf" or not e.context:
            out.append(e)
            continue
        branches = {}
        for sub in e.context:
            branches.setdefault(sub.schema_path[0], []).append(sub)
        picked = [b for b in branches.values()
                  if not any(list(x.path)[-1:] == ["analysis"] for x in b)]
        if len(picked) == 1:
            out.extend(leaves(picked[0]))
        else:
            out.append(e)
    return out


FORMATS = jsonschema.FormatChecker(formats=())


@FORMATS.checks("date-time", raises=ValueError)
def _date_time(value):
    if not isinstance(value, str):
        return True
    if not re.match(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?(Z|[+-]\d\d:\d\d)$", value):
        raise ValueError("not an RFC 3339 date-time")
    return True


# ---- the live server ---------------------------------------------------------
class Server:
    def __init__(self, binary, args):
        self.err = tempfile.TemporaryFile()
        self.proc = subprocess.Popen(
            [binary, "--host", "127.0.0.1", "--port", "0", "--data", ":memory:"] + args,
            stdout=subprocess.PIPE, stderr=self.err)
        line = self.proc.stdout.readline().decode()
        m = re.match(r"^ringdyn-server listening on (http://127\.0\.0\.1:\d+)$", line.strip())
        if not m:
            self.err.seek(0)
            sys.exit("server did not start: %r %s" % (line, self.err.read().decode()[-2000:]))
        self.base = m.group(1)

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            return self.proc.wait(30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return -1


class Headers(dict):
    def get(self, key, default=None):
        return dict.get(self, key.lower(), default)


def oversized(base, path, length):
    """POST with a Content-Length over the limit and no body: the server
    answers before reading it (urllib would break on the closed pipe)."""
    host, port = base[len("http://"):].split(":")
    with socket.create_connection((host, int(port)), timeout=30) as sock:
        sock.sendall(("POST %s HTTP/1.1\r\nHost: %s:%s\r\nContent-Type: application/json\r\n"
                      "Content-Length: %d\r\nConnection: close\r\n\r\n" %
                      (path, host, port, length)).encode())
        data = b""
        while True:
            chunk = sock.recv(65536)
            if not chunk:
                break
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    h = Headers((k.strip().lower(), v.strip()) for k, _, v in
                (ln.partition(":") for ln in lines[1:]))
    return int(lines[0].split()[1]), h, body


def http(base, method, path, body=None, headers=None, ctype="application/json"):
    if method == "POST" and isinstance(body, int):
        return oversized(base, path, body)
    data = body if isinstance(body, (bytes, type(None))) else body.encode()
    req = urllib.request.Request(base + path, data=data, method=method)
    if data is not None and ctype:
        req.add_header("Content-Type", ctype)
    for k, v in (headers or {}).items():
        req.add_header(k, v)
    try:
        with urllib.request.urlopen(req, timeout=300) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers, e.read()


def replay(doc_file, dump_file):
    """contract.py --replay DOC DUMP: the answers a run saved (CONTRACT_DUMP=
    file) checked again against DOC, without a server (for editing DOC)."""
    c = Contract(json.load(open(doc_file)))
    for line in open(dump_file):
        name, method, path, st, ctype, body = json.loads(line)
        c.check(name, method, path, st, ctype, body.encode())
    print("%d passed, %d failed" % (PASSED, FAILED))
    sys.exit(1 if FAILED else 0)


def answers(doc_file, folder):
    """contract.py --answers DOC DIR: the answers an HTTP test script kept
    (tests/http/lib.sh: N.meta holds method, path, status, Content-Type and
    Content-Encoding, tab-separated; N.body the body) checked against DOC.
    libmicrohttpd's own error pages (HTML, for requests it refuses before
    ringdyn sees them: README, docs/service.md) are outside the contract and
    counted apart."""
    global QUIET
    QUIET = True
    c = Contract(json.load(open(doc_file)))
    metas = sorted((f for f in os.listdir(folder) if f.endswith(".meta")),
                   key=lambda f: int(f.split(".")[0]))
    mhd = 0
    for f in metas:
        fields = open(os.path.join(folder, f), encoding="utf-8", errors="replace").read()
        method, path, status, ctype, cenc = (fields.rstrip("\n").split("\t") + [""] * 5)[:5]
        body = open(os.path.join(folder, f[:-5] + ".body"), "rb").read()
        if cenc.strip().lower() == "gzip" and body:
            body = gzip.decompress(body)
        if ctype.startswith("text/html") and int(status) >= 400 and b"ringdyn" not in body:
            mhd += 1
            continue
        c.check("%s %s (%s)" % (method, path, f[:-5]), method, path, int(status), ctype, body)
    print("contract: %d answers of this script validated against the served OpenAPI document "
          "(%d answer kinds), %d failed; %d libmicrohttpd pages left out" %
          (c.answers, len(c.seen), FAILED, mhd))
    sys.exit(1 if FAILED else 0)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--replay":
        replay(sys.argv[2], sys.argv[3])
    if len(sys.argv) == 4 and sys.argv[1] == "--answers":
        answers(sys.argv[2], sys.argv[3])
    if len(sys.argv) != 4:
        sys.exit("usage: contract.py SERVER EXAMPLES_DIR STATIC_DIR")
    binary, examples, static = sys.argv[1:4]
    # A: every functional answer; B (one worker, a queue of one): 429
    a = Server(binary, ["--examples", examples, "--static", static, "--threads", "2"])
    b = Server(binary, ["--threads", "1", "--queue", "1"])
    try:
        run(a.base, b.base)
    finally:
        for name, srv in (("A", a), ("B", b)):
            rc = srv.stop()
            if rc == 0:
                ok("server %s exits 0 after SIGTERM" % name)
            else:
                bad("server %s exits 0 after SIGTERM" % name, "exit %s" % rc)
    print("%d passed, %d failed" % (PASSED, FAILED))
    sys.exit(1 if FAILED else 0)


def run(base, base_b):
    st, h, body = http(base, "GET", "/api/v1/openapi.json")
    if st != 200:
        bad("GET /api/v1/openapi.json", "status %s" % st)
        return
    c = Contract(json.loads(body))

    dump = open(os.environ["CONTRACT_DUMP"], "w") if os.environ.get("CONTRACT_DUMP") else None

    def call(name, method, path, body=None, headers=None, ctype="application/json", on=None):
        st, h, b = http(on or base, method, path, body, headers, ctype)
        if dump:
            dump.write(json.dumps([name, method, path, st, h.get("Content-Type"),
                                   b.decode("utf-8", "replace")]) + "\n")
        return st, h, c.check(name, method, path, st, h.get("Content-Type"), b)

    from contract_cases import cases  # noqa: E402 (tests/http, beside this file)
    cases(call, base_b, ok, bad)

    documented = c.documented()
    missing = sorted(documented - c.seen)
    # Kinds a loopback server without a token cannot produce: access (401,
    # 403: http_access) and memory (503).
    skipped = {"401", "403", "503"}
    left = [k for k in missing if k[2] not in skipped]
    for k in left:
        print("note - not produced here: %s %s %s" % k)
    produced = len(c.seen & documented)
    total = len([k for k in documented if k[2] not in skipped])
    print("coverage: %d answers, each validated against the document; they cover %d of the %d "
          "documented (operation, status) kinds (401/403/503, access and memory, are "
          "http_access's and test_jobs')" % (c.answers, produced, total))


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    main()
