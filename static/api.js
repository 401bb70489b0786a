// The HTTP side of the page: JSON requests and the job life cycle of API.md.

// An error the page can show: the server's {"error":{code,message,path}} or a
// client-side failure (network, timeout) in the same shape.
export class ApiError extends Error {
  // `errors`: every problem the server found (its first is this one).
  constructor({ code = 'error', message = 'Unknown error', path = '', errors = null, errors_omitted: omitted = 0 } = {}, status = 0) {
    super(message);
    this.code = code;
    this.path = path || '';
    this.status = status;
    this.errors = Array.isArray(errors) ? errors.filter((e) => e && typeof e === 'object') : null;
    this.errors_omitted = Number(omitted) || 0;
  }
}

async function errorFrom(resp) {
  let body = null;
  try { body = await resp.json(); } catch { /* not JSON: fall back to the status line */ }
  const e = body && body.error ? { ...body.error, errors: body.errors, errors_omitted: body.errors_omitted } : { message: `HTTP ${resp.status} ${resp.statusText}` };
  if (resp.status === 429) {
    const after = resp.headers.get('Retry-After');
    e.message = `${e.message || 'The job queue is full'}${after ? ` — retry in ${after} s` : ''}`;
  }
  return new ApiError(e, resp.status);
}

// The access token of a server started with --token-file: opened once as
// /?token=TOKEN (then dropped from the address bar), or typed in when the server
// answers 401; kept in this browser's localStorage and sent as a Bearer header.
const TOKEN_KEY = 'ringdyn.token';
const storage = () => { try { return globalThis.localStorage ?? null; } catch { return null; } };
(() => {
  const loc = globalThis.location;
  const token = loc ? new URLSearchParams(loc.search).get('token') : null;
  if (!token) return;
  storage()?.setItem(TOKEN_KEY, token);
  const url = new URL(loc.href);
  url.searchParams.delete('token');
  globalThis.history?.replaceState(null, '', url);
})();

function authHeaders() {
  const token = storage()?.getItem(TOKEN_KEY);
  return token ? { Authorization: `Bearer ${token}` } : {};
}

async function request(url, options = {}, read = (resp) => resp.json(), retried = false) {
  let resp;
  try {
    resp = await fetch(url, { ...options, headers: { Accept: 'application/json', ...authHeaders(), ...options.headers } });
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    throw new ApiError({ code: 'network', message: `Cannot reach the ringdyn server (${e.message}).` });
  }
  if (resp.status === 401 && !retried && globalThis.prompt) {
    const token = globalThis.prompt('This ringdyn server needs its access token (the --token-file):');
    if (token) {
      storage()?.setItem(TOKEN_KEY, token.trim());
      return request(url, options, read, true);
    }
  }
  if (!resp.ok) throw await errorFrom(resp);
  return { status: resp.status, body: await read(resp) };
}

export async function getJSON(url, options) {
  return (await request(url, options)).body;
}

// A table (result.csv) as a Blob; errors as for JSON requests.
export async function getBlob(url, options) {
  return (await request(url, options, (resp) => resp.blob())).body;
}

// Every final status (interrupted: the server stopped while the job ran).
const FINISHED = new Set(['succeeded', 'failed', 'cancelled', 'interrupted']);
// Polls soon after the submission (a short job is then shown at once), then
// long-polls (GET ?wait=LONG_POLL_S): answered as soon as the job ends, else
// after that long with its progress.
const POLL_MS = [100, 200, 300];
const LONG_POLL_S = 1;
const POLL_LIMIT_S = 900; // give up polling after 15 min (the job keeps its id)

const sleep = (ms, signal) => new Promise((resolve, reject) => {
  const t = setTimeout(resolve, ms);
  signal?.addEventListener('abort', () => { clearTimeout(t); reject(new DOMException('Aborted', 'AbortError')); }, { once: true });
});

// Submits a scene and resolves with the finished job ({id, status, result|error}).
// POST ?wait=S answers 200 with the finished job, or 202 if it is still
// running: then watchJob polls it.  onUpdate(job) sees every intermediate
// state, the first one as soon as the job has an id.
export async function runJob(scene, { wait = 0, signal, onUpdate = () => {} } = {}) {
  const { status, body: job } = await request(`/api/v1/jobs?wait=${wait}`, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', Accept: 'application/json' },
    body: JSON.stringify(scene),
    signal,
  });
  if (status !== 202 && FINISHED.has(job.status)) return job;
  return watchJob(job, { signal, onUpdate });
}

// Polls job `job` ({id, status}, or just its id) until it has finished.
export async function watchJob(job, { signal, onUpdate = () => {} } = {}) {
  if (typeof job === 'string') job = await getJSON(jobUrl(job), { signal });
  const deadline = Date.now() + POLL_LIMIT_S * 1000;
  for (let i = 0; !FINISHED.has(job.status); i++) {
    onUpdate(job);
    if (Date.now() > deadline) {
      throw new ApiError({ code: 'timeout', message: `Job ${job.id} is still ${job.status}; stopped waiting after ${POLL_LIMIT_S / 60} min. Its result will be at /api/v1/jobs/${job.id}.` });
    }
    const quick = i < POLL_MS.length;
    if (quick) await sleep(POLL_MS[i], signal);
    const asked = Date.now();
    job = await getJSON(quick ? jobUrl(job.id) : `${jobUrl(job.id)}?wait=${LONG_POLL_S}`, { signal });
    // Not held (a proxy in the way): do not poll in a tight loop.
    if (!quick && !FINISHED.has(job.status) && Date.now() - asked < 100) await sleep(500, signal);
  }
  return job;
}

export function cancelJob(id) {
  return fetch(jobUrl(id), { method: 'DELETE', headers: authHeaders() }).catch(() => {});
}

export function jobUrl(id, suffix = '') {
  return `/api/v1/jobs/${encodeURIComponent(id)}${suffix}`;
}

// POST a JSON body (e.g. a sweep spec); resolves with the answer's JSON.
export async function postJSON(url, body, { signal } = {}) {
  return (await request(url, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', Accept: 'application/json' },
    body: JSON.stringify(body),
    signal,
  })).body;
}

// DELETE `url` (a sweep); resolves with the Response, or undefined when unreachable.
export function deleteUrl(url) {
  return fetch(url, { method: 'DELETE', headers: authHeaders() }).catch(() => {});
}
