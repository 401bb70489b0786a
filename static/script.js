// The form as a script: a scene turned into a curl command or a Python
// program (standard library only) that submits it to this server, waits for
// the job and prints the result; and saving a Blob as a download.

// A shell word: single-quoted, a ' inside written as '\''.
const shellQuote = (s) => `'${String(s).replace(/'/g, `'\\''`)}'`;

// curl that submits `scene` and waits up to 300 s for the finished job
// (API.md: POST ?wait=S answers 200 with it, or 202 if it still runs).
export function curlText(scene, origin) {
  return [
    `curl -sS -X POST ${shellQuote(`${origin}/api/v1/jobs?wait=300`)} \\`,
    "  -H 'Content-Type: application/json' --data-binary @- <<'RINGDYN_SCENE'",
    JSON.stringify(scene, null, 2),
    'RINGDYN_SCENE',
    '',
  ].join('\n');
}

// A JSON value as a Python literal.  JSON string escapes are valid in Python
// string literals; numbers are finite (a scene holds no NaN or Infinity).
export function pyLiteral(v, indent = '') {
  if (v === null || v === undefined) return 'None';
  if (v === true) return 'True';
  if (v === false) return 'False';
  if (typeof v === 'number' || typeof v === 'string') return JSON.stringify(v);
  const inner = `${indent}    `;
  if (Array.isArray(v)) {
    if (v.every((x) => x === null || typeof x !== 'object')) return `[${v.map((x) => pyLiteral(x)).join(', ')}]`;
    return `[\n${v.map((x) => `${inner}${pyLiteral(x, inner)}`).join(',\n')},\n${indent}]`;
  }
  const keys = Object.keys(v);
  if (!keys.length) return '{}';
  return `{\n${keys.map((k) => `${inner}${JSON.stringify(k)}: ${pyLiteral(v[k], inner)}`).join(',\n')},\n${indent}}`;
}

// A Python 3 program (urllib.request and json only): submits `scene`, polls
// the job until it ends, prints the result as JSON; an error prints the
// server's message and the JSON Pointer of the field and exits non-zero.
export function pythonText(scene, origin) {
  return `import json
import sys
import time
import urllib.error
import urllib.request

BASE = ${JSON.stringify(origin)}
scene = ${pyLiteral(scene)}


def call(method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(BASE + path, data=data, method=method,
                                 headers={"Content-Type": "application/json", "Accept": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=60) as resp:
            return json.load(resp)
    except urllib.error.HTTPError as e:
        try:
            err = json.load(e).get("error", {})
        except ValueError:  # not a JSON error body
            err = {"message": e.reason}
        sys.exit(f"HTTP {e.code}: {err.get('message')} (path {err.get('path') or '-'})")


job = call("POST", "/api/v1/jobs?wait=10", scene)
while job["status"] in ("queued", "running"):
    time.sleep(0.5)
    job = call("GET", "/api/v1/jobs/" + job["id"])
if job["status"] != "succeeded":
    err = job.get("error", {})
    sys.exit(f"job {job['id']} {job['status']}: {err.get('message')} (path {err.get('path') or '-'})")
print(json.dumps(job["result"], indent=2))
`;
}

// Saves `blob` as a download named `name`.
export function saveBlob(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.hidden = true;
  document.body.append(a);
  a.click();
  a.remove();
  // The download has started from the URL; give it time before freeing it.
  setTimeout(() => URL.revokeObjectURL(a.href), 60000);
}
