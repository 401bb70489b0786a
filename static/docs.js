// The API docs page (/docs): renders the server's own OpenAPI document
// (/api/v1/openapi.json) as a readable page — every operation with its
// parameters, request body, responses and examples, then every schema with
// its fields (type, range, default, description).  Nothing is copied into
// the page: what the document says is what is shown.  DOM nodes only (no
// innerHTML): every text comes from the document and is shown as text.

const METHODS = ['get', 'put', 'post', 'delete', 'patch', 'head', 'options'];

// Appends children to `e`: nodes, text, arrays of them (flattened);
// null, undefined and false are skipped.
function add(e, ...children) {
  for (const c of children.flat(Infinity)) {
    if (c === undefined || c === null || c === false) continue;
    e.append(c instanceof Node ? c : String(c));
  }
  return e;
}

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'class') e.className = v;
    else e.setAttribute(k, v === true ? '' : v);
  }
  return add(e, children);
}

const schemaId = (name) => `schema-${name}`;
const opId = (method, path, op) => `op-${op.operationId || `${method}-${path.replace(/[^A-Za-z0-9]+/g, '-')}`}`;
const refName = (ref) => (typeof ref === 'string' && ref.startsWith('#/components/schemas/') ? ref.slice(21) : null);

// Text paragraphs from a description (blank lines separate paragraphs;
// `code` spans are kept as code).
function prose(text, cls = 'desc') {
  if (!text) return null;
  return String(text).split(/\n\s*\n/).map((para) => {
    const p = el('p', { class: cls });
    para.split(/(`[^`]+`)/).forEach((part) => {
      if (/^`[^`]+`$/.test(part)) p.append(el('code', {}, part.slice(1, -1)));
      else if (part) p.append(part);
    });
    return p;
  });
}

// A short type for a schema: "number", "array of Mode", a link for a $ref.
function typeOf(s) {
  if (!s || typeof s !== 'object') return 'any';
  const name = refName(s.$ref);
  if (name) return el('a', { href: `#${schemaId(name)}` }, name);
  for (const k of ['oneOf', 'anyOf', 'allOf']) {
    if (Array.isArray(s[k])) {
      const span = el('span');
      s[k].forEach((sub, i) => { if (i) span.append(k === 'allOf' ? ' & ' : ' | '); span.append(typeOf(sub)); });
      return span;
    }
  }
  if (s.type === 'array') return el('span', {}, 'array of ', typeOf(s.items));
  return s.type || 'any';
}

// "≥ 0.001, ≤ 5", enums, item counts, default: the constraints of a schema.
function constraints(s) {
  if (!s || typeof s !== 'object') return '';
  const out = [];
  if (s.minimum !== undefined) out.push(`${s.exclusiveMinimum === true ? '>' : '≥'} ${s.minimum}`);
  if (s.maximum !== undefined) out.push(`${s.exclusiveMaximum === true ? '<' : '≤'} ${s.maximum}`);
  if (s.minItems !== undefined) out.push(`at least ${s.minItems} items`);
  if (s.maxItems !== undefined) out.push(`at most ${s.maxItems} items`);
  if (Array.isArray(s.enum)) out.push(`one of ${s.enum.map((v) => JSON.stringify(v)).join(', ')}`);
  if (s.default !== undefined) out.push(`default ${JSON.stringify(s.default)}`);
  return out.join('; ');
}

function jsonBlock(value, label) {
  const pre = el('pre', { class: 'json', tabindex: '0', 'aria-label': label }, JSON.stringify(value, null, 2));
  return pre;
}

function table(caption, head, rows) {
  if (!rows.length) return null;
  return el('div', { class: 'table-wrap' },
    el('table', {},
      el('caption', {}, caption),
      el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
      el('tbody', {}, rows.map((r) => el('tr', {}, r.map((c) => el('td', {}, c)))))));
}

function parameters(op, pathItem) {
  const params = [...(pathItem.parameters || []), ...(op.parameters || [])];
  return table('Parameters', ['Name', 'In', 'Type', 'Description'], params.map((p) => [
    el('code', {}, p.name + (p.required ? '' : '?')), p.in,
    el('span', {}, typeOf(p.schema), constraints(p.schema) ? ` (${constraints(p.schema)})` : ''),
    el('span', {}, prose(p.description) || '')]));
}

function examplesOf(media) {
  const out = [];
  if (media.example !== undefined) out.push(jsonBlock(media.example, 'Example'));
  for (const [name, ex] of Object.entries(media.examples || {})) {
    out.push(el('p', { class: 'ex-title' }, `Example “${name}”${ex.summary ? `: ${ex.summary}` : ''}`));
    if (ex.value !== undefined) out.push(jsonBlock(ex.value, `Example ${name}`));
  }
  return out;
}

function content(c) {
  if (!c) return [];
  return Object.entries(c).map(([type, media]) => el('div', { class: 'media' },
    el('p', {}, el('code', {}, type), media.schema ? ' — ' : '', media.schema ? typeOf(media.schema) : ''),
    examplesOf(media)));
}

function responses(op, doc) {
  const out = [el('h4', {}, 'Responses')];
  for (const [code, r0] of Object.entries(op.responses || {})) {
    const ref = r0.$ref && r0.$ref.replace('#/components/responses/', '');
    const r = ref ? (doc.components?.responses?.[ref] || {}) : r0;
    out.push(el('div', { class: 'response' },
      el('p', {}, el('strong', { class: `code c${code[0]}` }, code), ' ', r.description || ''),
      content(r.content)));
  }
  return out;
}

function operation(doc, path, method, op, pathItem) {
  const sec = el('section', { class: 'op', id: opId(method, path, op), 'aria-labelledby': `${opId(method, path, op)}-h` },
    el('h3', { id: `${opId(method, path, op)}-h` },
      el('span', { class: `method m-${method}` }, method.toUpperCase()), ' ',
      el('code', { class: 'path' }, path)),
    op.summary ? el('p', { class: 'summary' }, op.summary) : null,
    prose(op.description),
    Array.isArray(op.security) && op.security.length === 0 ? el('p', { class: 'hint' }, 'No token needed.') : null,
    parameters(op, pathItem));
  if (op.requestBody) {
    add(sec, el('h4', {}, 'Request body'), ...(prose(op.requestBody.description) || []), ...content(op.requestBody.content));
  }
  add(sec, responses(op, doc));
  return sec;
}

// The rows of an object's fields; an inline object's own fields follow it
// as "outer/inner" (its JSON Pointer below the object).
function fieldRows(s, prefix = '') {
  const required = new Set(s.required || []);
  return Object.entries(s.properties || {}).flatMap(([key, p]) => [
    [el('code', {}, prefix + key + (required.has(key) ? '' : '?')), typeOf(p), constraints(p),
      el('span', {}, prose(p.description) || '')],
    ...(p && p.properties && !p.$ref ? fieldRows(p, `${prefix}${key}/`) : []),
  ]);
}

function schemaSection(name, s) {
  const props = Object.entries(s.properties || {});
  const rows = fieldRows(s);
  const sec = el('section', { class: 'schema', id: schemaId(name), 'aria-labelledby': `${schemaId(name)}-h` },
    el('h3', { id: `${schemaId(name)}-h` }, name),
    prose(s.description));
  const combo = ['oneOf', 'anyOf', 'allOf'].find((k) => Array.isArray(s[k]));
  if (combo) add(sec, el('p', {}, combo === 'allOf' ? 'All of: ' : 'One of: ', typeOf(s)));
  if (s.discriminator) add(sec, el('p', { class: 'hint' }, `Chosen by the value of “${s.discriminator.propertyName}”.`));
  if (s.type === 'array') add(sec, el('p', {}, 'An array of ', typeOf(s.items)));
  if (!props.length && !combo && s.type !== 'object' && s.type !== 'array') add(sec, el('p', {}, typeOf(s), constraints(s) ? ` (${constraints(s)})` : ''));
  const t = table(`Fields of ${name} (? marks an optional field)`, ['Field', 'Type', 'Allowed', 'Description'], rows);
  if (t) add(sec, t);
  if (s.additionalProperties === false) add(sec, el('p', { class: 'hint' }, 'No other fields are allowed.'));
  return sec;
}

function intro(doc) {
  const info = doc.info || {};
  const sec = document.getElementById('docs-intro');
  add(sec, 
    el('h2', { id: 'docs-title' }, `${info.title || 'API'} ${info.version || ''}`.trim()),
    prose(info.description) || '',
    el('p', {}, 'Servers: ', (doc.servers || []).map((s) => s.url).join(', ') || '/'));
  const schemes = doc.components?.securitySchemes || {};
  for (const [name, s] of Object.entries(schemes)) {
    add(sec, el('p', {}, el('strong', {}, `Authentication (${name}): `), `${s.type}${s.scheme ? ` ${s.scheme}` : ''}. `, s.description || ''));
  }
  if (info.license) {
    add(sec, el('p', { id: 'license' }, el('strong', {}, 'License: '), info.license.name || ''));
  }
}

function toc(doc, ops) {
  const nav = document.getElementById('docs-toc');
  const byTag = new Map();
  for (const o of ops) {
    const tag = (o.op.tags && o.op.tags[0]) || 'other';
    if (!byTag.has(tag)) byTag.set(tag, []);
    byTag.get(tag).push(o);
  }
  add(nav, el('h2', {}, 'Operations'));
  const tags = new Map((doc.tags || []).map((t) => [t.name, t.description]));
  for (const [tag, list] of byTag) {
    add(nav, el('h3', {}, tag), tags.get(tag) ? el('p', { class: 'hint' }, tags.get(tag)) : null,
      el('ul', { class: 'toc' }, list.map((o) => el('li', {},
        el('a', { href: `#${opId(o.method, o.path, o.op)}` },
          el('span', { class: `method m-${o.method}` }, o.method.toUpperCase()), ' ',
          el('code', { class: 'path' }, o.path)),
        o.op.summary ? ` — ${o.op.summary}` : ''))));
  }
  const names = Object.keys(doc.components?.schemas || {});
  if (names.length) {
    add(nav, el('h3', {}, 'Schemas'),
      el('p', { class: 'schema-links' }, names.flatMap((n, i) => [i ? ', ' : '', el('a', { href: `#${schemaId(n)}` }, n)])));
  }
}

async function main() {
  const status = document.getElementById('docs-status');
  let doc;
  try {
    const resp = await fetch('/api/v1/openapi.json');
    if (!resp.ok) throw new Error(`HTTP ${resp.status}`);
    doc = await resp.json();
  } catch (e) {
    status.textContent = `The OpenAPI document could not be loaded (${e.message}).`;
    return;
  }
  const ops = [];
  for (const [path, item] of Object.entries(doc.paths || {})) {
    for (const method of METHODS) if (item[method]) ops.push({ path, method, op: item[method], item });
  }
  intro(doc);
  toc(doc, ops);
  const opsSec = document.getElementById('docs-operations');
  add(opsSec, el('h2', {}, 'Operations in detail'), ...ops.map((o) => operation(doc, o.path, o.method, o.op, o.item)));
  const schSec = document.getElementById('docs-schemas');
  add(schSec, el('h2', {}, 'Schemas'), ...
    Object.entries(doc.components?.schemas || {}).map(([n, s]) => schemaSection(n, s)));
  for (const id of ['docs-intro', 'docs-toc', 'docs-operations', 'docs-schemas']) document.getElementById(id).hidden = false;
  status.hidden = true;
  document.getElementById('docs').dataset.ready = String(ops.length);
  // A link to #fragment followed before rendering: go there now.
  if (location.hash) document.getElementById(decodeURIComponent(location.hash.slice(1)))?.scrollIntoView();
}

main();
