// The scene form: every input carries data-path (the JSON Pointer of its scene
// field) and data-default.  The scene is read from those inputs, an example is
// written into them, and an error's path finds the input to highlight.

const HINTS = {
  mm: (v) => `= ${fmt(v * 1e3)} mm`,
  GPa: (v) => `= ${fmt(v / 1e9)} GPa`,
};

function fmt(v) {
  return Number(v.toPrecision(6)).toString();
}

export class SceneForm {
  constructor(form) {
    this.form = form;
    this.inputs = [...form.querySelectorAll('[data-path]')];
    for (const input of this.inputs) {
      if (input.dataset.hint) this.addHint(input);
      input.addEventListener('input', () => {
        this.updateHint(input);
        this.unmark(input);
      });
    }
    this.reset();
  }

  addHint(input) {
    const hint = document.createElement('span');
    hint.className = 'unit-hint';
    hint.id = `${input.id}-hint`;
    input.after(hint);
    input.setAttribute('aria-describedby', [input.getAttribute('aria-describedby'), hint.id].filter(Boolean).join(' '));
  }

  updateHint(input) {
    const fn = HINTS[input.dataset.hint];
    const hint = fn && document.getElementById(`${input.id}-hint`);
    if (!hint) return;
    const v = input.valueAsNumber;
    hint.textContent = Number.isFinite(v) ? fn(v) : '';
  }

  // Inputs that belong to `analysis`: the shared ones plus its own fieldset.
  inputsFor(analysis) {
    return this.inputs.filter((input) => {
      const owner = input.closest('[data-analysis]');
      return !owner || owner.dataset.analysis === analysis;
    });
  }

  showAnalysis(analysis) {
    for (const fs of this.form.querySelectorAll('[data-analysis]')) {
      fs.hidden = fs.dataset.analysis !== analysis;
    }
  }

  reset() {
    this.base = {};
    for (const input of this.inputs) setValue(input, input.dataset.default);
    this.clearMarks();
    this.updateHints();
  }

  updateHints() {
    for (const input of this.inputs) this.updateHint(input);
  }

  // Fills the form from a scene: fields the scene lacks get their defaults;
  // scene fields the form has no input for are kept and sent with it.
  load(scene) {
    this.reset();
    const { name, description, ...rest } = scene;
    this.base = structuredClone(rest);
    for (const input of this.inputs) {
      const v = pointerGet(scene, input.dataset.path);
      if (v !== undefined && v !== null && typeof v !== 'object') setValue(input, v);
    }
    this.updateHints();
  }

  // Builds the scene for `analysis`.  Throws {message, path} for an empty or
  // non-numeric field; ranges are the server's to check (one source of truth).
  read(analysis) {
    const scene = { ...structuredClone(this.base), analysis };
    for (const input of this.inputsFor(analysis)) {
      let v;
      if (input.type === 'checkbox') {
        v = input.checked;
      } else {
        v = input.valueAsNumber;
        if (!Number.isFinite(v)) {
          throw { code: 'invalid_value', message: 'must be a number', path: input.dataset.path };
        }
        if (input.dataset.type === 'int' && !Number.isInteger(v)) {
          throw { code: 'invalid_value', message: `must be a whole number, got ${v}`, path: input.dataset.path };
        }
      }
      pointerSet(scene, input.dataset.path, v);
    }
    return scene;
  }

  // The inputs an error path points at: the exact field, else the fields
  // below it ("/ring/material"), else the nearest field above it.
  fieldsFor(path) {
    if (!path) return [];
    const exact = this.inputs.filter((i) => i.dataset.path === path);
    if (exact.length) return exact;
    const below = this.inputs.filter((i) => i.dataset.path.startsWith(`${path}/`));
    if (below.length) return below;
    const above = this.inputs
      .filter((i) => path.startsWith(`${i.dataset.path}/`))
      .sort((a, b) => b.dataset.path.length - a.dataset.path.length);
    return above.slice(0, 1);
  }

  // What to call a group of fields from fieldsFor(): the field's label, or
  // for several fields their fieldset's legend.
  nameOf(fields) {
    const text = (el) => el?.textContent.replace(/\s+/g, ' ').trim();
    if (fields.length > 1) return text(fields[0].closest('fieldset')?.querySelector('legend')) || fields[0].dataset.path;
    return text(this.form.querySelector(`label[for="${fields[0].id}"]`)) || fields[0].dataset.path;
  }

  // Highlights the fields of an error path; returns them (first one focused).
  mark(path, errorId) {
    const fields = this.fieldsFor(path);
    for (const input of fields) {
      input.setAttribute('aria-invalid', 'true');
      input.setAttribute('aria-errormessage', errorId);
      input.closest('.field')?.classList.add('invalid');
    }
    // Centred, so the sticky run bar (which shows the message) does not cover it.
    fields[0]?.focus({ preventScroll: true });
    fields[0]?.scrollIntoView({ block: 'center' });
    return fields;
  }

  unmark(input) {
    input.removeAttribute('aria-invalid');
    input.removeAttribute('aria-errormessage');
    input.closest('.field')?.classList.remove('invalid');
  }

  clearMarks() {
    for (const input of this.inputs) this.unmark(input);
  }
}

function setValue(input, v) {
  if (input.type === 'checkbox') input.checked = v === true || v === 'true';
  else input.value = v === undefined ? '' : String(v);
}

// JSON Pointer (RFC 6901) get / set on plain objects.
function tokens(path) {
  return path.split('/').slice(1).map((t) => t.replace(/~1/g, '/').replace(/~0/g, '~'));
}

export function pointerGet(obj, path) {
  let cur = obj;
  for (const t of tokens(path)) {
    if (cur === null || typeof cur !== 'object') return undefined;
    cur = cur[t];
  }
  return cur;
}

function pointerSet(obj, path, value) {
  const ts = tokens(path);
  let cur = obj;
  for (const t of ts.slice(0, -1)) {
    if (typeof cur[t] !== 'object' || cur[t] === null) cur[t] = {};
    cur = cur[t];
  }
  cur[ts[ts.length - 1]] = value;
}
