// The scene form: every input carries data-path (the JSON Pointer of its scene
// field); its data-default comes from the server's OpenAPI document
// (setDefaults), whose scene schemas the server writes from the same tables
// that parse scenes, so the page holds no copy of a default.  The scene is
// read from those inputs, an example is written into them, and an error's
// path finds the input to highlight.
//
// Encoding of a field by its element:
//   checkbox                    -> true / false
//   <select>                    -> the chosen option's value (a string choice)
//   number                      -> a number; data-type="int" requires a whole one;
//                                  data-word="w" (a text input): the number or
//                                  the word w itself (e.g. cycles "periodic");
//                                  data-optional: left empty, the field is absent
//                                  from the scene (the server's default applies);
//                                  with required too, no default is filled in
//                                  but it must not be left empty
// Structures:
//   [data-list="/ptr"]          an editable list of rows (a <template> holds one
//                               row; its inputs name their key with data-field);
//                               0 rows = the field is absent.  data-max caps it.
//                               The rows sit in the list's <tbody>, or in its
//                               [data-rows] element (rows that are not table
//                               rows).  A row may hold a list of its own (an
//                               element [data-list][data-field="key"] in the
//                               template): its rows are the row's array at that
//                               key, left out when it has none (a bore map's
//                               layers, each with its distortion orders).
//                               In a row, data-label="… {n} …" gives a label (a
//                               button's aria-label) the row's number; {p} is the
//                               number of the row the list sits in.  An input's
//                               data-next="step": a row added after one whose
//                               value is a number starts at that value + step.
//   input[data-toggle="/ptr"]   a checkbox that puts a whole block in the scene;
//                               unchecked, the block is absent.  The inputs of
//                               that block sit in [data-block="/ptr"].
//   select[data-source="/ptr"]  for a toggled block: which prepared object
//                               (setSource) the block starts from, e.g. the gas
//                               pressure tables of an example.
//   [data-when="id"]            fields that count only while the <select> of
//     data-when-in="a b"        that id has one of these values (a friction
//     data-clear="/p /q"        model's own inputs); otherwise hidden, and they
//                               and the data-clear paths are left out of the
//                               scene (also what a loaded scene had there).
//                               Nested ones must all hold.  The id of a
//                               [data-list] has the value "rows" while the list
//                               has rows, else "none" (the fields a bore map
//                               needs; the distortion a map replaces).
//   input[data-word-for="id"]   a checkbox that sends its data-word instead of
//     data-word="w"             the number of the input of that id (disabled
//                               while checked); a loaded scene with the word
//                               there checks it (contact height "all").
//   [data-each="/ptr"]          a <template> repeated once per element of the
//                               array at /ptr in the loaded scene (at least
//                               once): in each copy "{i}" in the attributes
//                               becomes the element's index and "{n}" in the
//                               attributes and text its number (index + 1),
//                               e.g. data-path="/rings/{i}/ring/face/profile".
//   select[data-mode]           such a <select> that is no scene field itself
//                               (which of two inputs to send); a loaded scene
//                               picks the first option whose data-if-set path
//                               it sets to a non-zero value, else the first.

const HINTS = {
  mm: (v) => `= ${fmt(v * 1e3)} mm`,
  um: (v) => `= ${fmt(v * 1e6)} µm`,
  GPa: (v) => `= ${fmt(v / 1e9)} GPa`,
  percent: (v) => `= ${fmt(v * 100)} %`,
};

function fmt(v) {
  return Number(v.toPrecision(6)).toString();
}

// The scene path an element writes: a field's data-path, a toggle's block.
const pathOf = (el) => el.dataset.path ?? el.dataset.toggle;

export class SceneForm {
  constructor(form) {
    this.form = form;
    this.analysis = null;
    this.base = {};
    this.baseAnalysis = null; // the analysis of the loaded scene (`base`)
    this.reads = new Map(); // analysis -> drops from a scene what the analysis does not read (OpenAPI)
    this.fieldPaths = new Map(); // analysis -> (path, scene) => the paths a shared field writes
    this.sources = new Map(); // block path -> Map(option value -> object)
    for (const input of this.inputs) if (input.dataset.hint) this.addHint(input);
    this.setupLists();
    this.eaches = [...form.querySelectorAll('[data-each]')];
    form.addEventListener('input', (e) => {
      const input = e.target.closest('[data-path], [data-toggle]');
      if (!input) return;
      this.updateHint(input);
      this.unmark(input);
    });
    form.addEventListener('change', (e) => {
      if (e.target.dataset.toggle) this.syncToggle(e.target);
      this.syncWhens();
    });
    this.reset();
  }

  // Each field's default from the OpenAPI document: the schema of the
  // field's analysis (its fieldset's data-analysis; the shared fields use
  // `shared`'s), followed along data-path.  Optional fields (data-optional)
  // stay empty: absent from the scene, the server's default applies.
  setDefaults(openapi, shared) {
    const schemas = openapi?.components?.schemas ?? {};
    const mapping = schemas.Scene?.discriminator?.mapping ?? {};
    const resolve = (s) => {
      const ref = s?.$ref ?? s?.allOf?.[0]?.$ref;
      return ref ? schemas[ref.split('/').pop()] : s;
    };
    for (const [analysis, ref] of Object.entries(mapping)) {
      const schema = resolve({ $ref: ref });
      if (schema?.properties) this.reads.set(analysis, (value) => prune(value, schema, resolve));
    }
    // A repeated template's fields: the first copy's path (the schema's items).
    const fields = [
      ...[...this.form.querySelectorAll('[data-path]')].map((input) => [input, input]),
      ...this.eaches.flatMap((each) => [...each.querySelector('template').content.querySelectorAll('[data-path]')].map((input) => [input, each])),
    ];
    for (const [input, at] of fields) {
      if ('optional' in input.dataset) continue;
      const analysis = at.closest('[data-analysis]')?.dataset.analysis ?? shared;
      let schema = resolve({ $ref: mapping[analysis] });
      for (const t of tokens(input.dataset.path.replaceAll('{i}', '0'))) {
        const s = resolve(schema);
        schema = resolve(/^\d+$/.test(t) ? s?.items : s?.properties?.[t]);
      }
      const d = schema?.default;
      if (d !== undefined) input.dataset.default = typeof d === 'number' ? formatDefault(d) : String(d);
    }
    this.reset();
  }

  // Live: list rows come and go.
  get inputs() {
    return [...this.form.querySelectorAll('[data-path], [data-toggle]')];
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
    const hint = fn && input.nextElementSibling?.classList.contains('unit-hint') ? input.nextElementSibling : null;
    if (!hint) return;
    const v = input.valueAsNumber;
    hint.textContent = Number.isFinite(v) ? fn(v) : '';
  }

  // Inputs that belong to `analysis`: the shared ones plus its own fieldset,
  // less the shared ones it has no place for.
  inputsFor(analysis) {
    return this.inputs.filter((input) => ownedBy(input, analysis) && this.pathsOf(input, analysis).length);
  }

  // Where `analysis` reads a shared field: its data-path, unless the
  // analysis maps it (setFieldPaths: the ring pack reads the Ring fields in
  // its first ring); [] = the analysis has no such field.  `scene` is the
  // scene being read or loaded (a mapping may depend on it).
  pathsOf(input, analysis, scene = this.base) {
    const path = pathOf(input);
    const map = this.fieldPaths.get(analysis);
    return map && !input.closest('[data-analysis]') && input.dataset.path ? map(path, scene) : [path];
  }

  setFieldPaths(analysis, fn) {
    this.fieldPaths.set(analysis, fn);
  }

  showAnalysis(analysis) {
    this.analysis = analysis;
    for (const fs of this.form.querySelectorAll('[data-analysis]')) {
      fs.hidden = fs.dataset.analysis !== analysis;
    }
    // A shared field the analysis has no place for is shown off (not sent).
    for (const input of this.inputs) {
      if (!input.dataset.path || input.closest('[data-analysis]')) continue;
      const off = !this.pathsOf(input, analysis).length;
      input.disabled = off;
      input.closest('.field')?.classList.toggle('off', off);
    }
  }

  reset() {
    this.base = {};
    this.baseAnalysis = null;
    for (const list of this.lists) this.setRows(list, []);
    for (const each of this.eaches) this.setCopies(each, 1);
    for (const input of this.inputs) setValue(input, input.dataset.default);
    for (const select of this.form.querySelectorAll('[data-source]')) select.selectedIndex = preferredIndex(select);
    for (const select of this.form.querySelectorAll('select[data-mode]')) select.selectedIndex = 0;
    for (const box of this.form.querySelectorAll('[data-word-for]')) box.checked = false;
    this.syncToggles();
    this.clearMarks();
    this.updateHints();
    this.changed();
  }

  // The lists that are no row's own (a row's list is filled with its row).
  get lists() {
    return [...this.form.querySelectorAll('[data-list]')].filter((l) => !l.parentElement.closest('[data-list]'));
  }

  // Tells listeners (the live bore map) that the form changed without an
  // input event: loaded, reset, a list row added or removed.
  changed() {
    this.form.dispatchEvent(new CustomEvent('formchange'));
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
    const analysis = scene.analysis ?? this.analysis;
    this.baseAnalysis = analysis;
    for (const list of this.lists) {
      const rows = pointerGet(scene, list.dataset.list);
      if (Array.isArray(rows)) this.setRows(list, rows);
    }
    for (const each of this.eaches) {
      const items = pointerGet(scene, each.dataset.each);
      this.setCopies(each, Array.isArray(items) ? Math.max(1, items.length) : 1);
    }
    for (const input of this.inputs) {
      if (input.dataset.toggle) {
        const block = pointerGet(scene, input.dataset.toggle);
        input.checked = block !== null && typeof block === 'object';
        if (input.checked) this.matchSource(input.dataset.toggle, block);
        continue;
      }
      const [at] = this.pathsOf(input, analysis, scene);
      const v = at === undefined ? undefined : pointerGet(scene, at);
      if (v !== undefined && v !== null && typeof v !== 'object') setValue(input, v);
    }
    for (const select of this.form.querySelectorAll('select[data-mode]')) {
      const set = (o) => o.dataset.ifSet && ![undefined, null, 0, false, ''].includes(pointerGet(scene, o.dataset.ifSet));
      select.value = ([...select.options].find(set) || select.options[0])?.value ?? '';
    }
    for (const box of this.form.querySelectorAll('[data-word-for]')) {
      const target = document.getElementById(box.dataset.wordFor);
      const [at] = target ? this.pathsOf(target, analysis, scene) : [];
      box.checked = at !== undefined && pointerGet(scene, at) === box.dataset.word;
    }
    this.syncToggles();
    this.updateHints();
    this.changed();
  }

  // Builds the scene for `analysis`.  Throws {message, path} for an empty or
  // non-numeric field; ranges are the server's to check (one source of truth).
  // A scene loaded for another analysis (then another tab chosen) keeps only
  // what this analysis reads, by its schema: the server refuses the rest.  A
  // scene loaded for this analysis goes as it is: its mistakes are the
  // server's to name, not the page's to drop.
  read(analysis) {
    const scene = { ...structuredClone(this.base), analysis };
    if (this.baseAnalysis && this.baseAnalysis !== analysis) this.reads.get(analysis)?.(scene);
    const mine = this.inputsFor(analysis);
    // Toggled blocks first, so their fields below land in them.
    for (const toggle of mine.filter((i) => i.dataset.toggle)) {
      const path = toggle.dataset.toggle;
      const kept = pointerGet(scene, path);
      pointerDelete(scene, path);
      if (!toggle.checked || toggle.disabled) continue;
      const start = kept !== null && typeof kept === 'object' && !Array.isArray(kept) ? kept : {};
      pointerSet(scene, path, { ...start, ...structuredClone(this.sourceValue(path) || {}) });
    }
    for (const list of this.lists) {
      if (!ownedBy(list, analysis) || this.isOff(list)) continue;
      const rows = this.readList(list);
      pointerDelete(scene, list.dataset.list);
      if (rows.length) pointerSet(scene, list.dataset.list, rows);
    }
    // Fields of a choice not taken, and their data-clear paths, go (even
    // where a loaded scene had them).
    for (const when of this.form.querySelectorAll('[data-when]')) {
      if (!ownedBy(when, analysis) || !this.isOff(when)) continue;
      for (const path of (when.dataset.clear || '').split(/\s+/).filter(Boolean)) pointerDelete(scene, path);
    }
    for (const input of mine) {
      if (input.dataset.toggle || input.closest('[data-list]')) continue;
      if (this.isOff(input)) {
        if (input.closest('[data-when]')) for (const at of this.pathsOf(input, analysis, scene)) pointerDelete(scene, at);
        continue;
      }
      const v = readValue(input);
      for (const at of this.pathsOf(input, analysis, scene)) {
        if (v === undefined) pointerDelete(scene, at);
        else pointerSet(scene, at, v);
      }
    }
    return scene;
  }

  // ---- toggled blocks --------------------------------------------------

  // Is `el` inside a block whose toggle is off, or a [data-when] whose
  // choice is not taken?
  isOff(el) {
    const block = el.closest('[data-block]');
    const toggle = block && this.toggleOf(block);
    if (toggle && (!toggle.checked || toggle.disabled)) return true;
    for (let w = el.closest('[data-when]'); w; w = w.parentElement?.closest('[data-when]')) {
      if (!whenHolds(w)) return true;
    }
    return false;
  }

  toggleOf(block) {
    const scope = block.closest('fieldset[data-analysis]') || this.form;
    return scope.querySelector(`[data-toggle="${block.dataset.block}"]`);
  }

  syncToggles() {
    for (const toggle of this.form.querySelectorAll('[data-toggle]')) this.syncToggle(toggle);
    this.syncWhens();
  }

  // A [data-when] shows while its choice is taken; its controls are enabled
  // while they count (their toggle on too).
  syncWhens() {
    for (const when of this.form.querySelectorAll('[data-when]')) {
      when.hidden = !whenHolds(when);
      for (const el of when.querySelectorAll('input, select, button')) el.disabled = this.isOff(el);
    }
    for (const box of this.form.querySelectorAll('[data-word-for]')) {
      const target = document.getElementById(box.dataset.wordFor);
      if (target) target.disabled = box.checked || this.isOff(target);
    }
    for (const list of this.form.querySelectorAll('[data-list]')) this.syncListButtons(list);
  }

  // A block's controls are disabled while its toggle is off; a toggle whose
  // block needs a source (gas tables) is disabled while there is none.
  syncToggle(toggle) {
    const scope = toggle.closest('fieldset[data-analysis]') || this.form;
    const path = toggle.dataset.toggle;
    const source = scope.querySelector(`[data-source="${path}"]`);
    if (source) {
      toggle.disabled = source.options.length === 0;
      if (toggle.disabled) toggle.checked = false;
    }
    for (const block of scope.querySelectorAll(`[data-block="${path}"]`)) {
      const on = toggle.checked && !toggle.disabled;
      block.classList.toggle('off', !on);
      for (const el of block.querySelectorAll('input, select, button')) el.disabled = !on;
    }
  }

  // The objects a toggled block can start from: [{value, label, title, data}];
  // `preferred` (a value) is selected by default.
  setSource(path, options, preferred) {
    const select = this.form.querySelector(`[data-source="${path}"]`);
    if (!select) return;
    const map = new Map();
    select.replaceChildren();
    for (const o of options) {
      const opt = document.createElement('option');
      opt.value = o.value;
      opt.textContent = o.label ?? o.value;
      if (o.title) opt.title = o.title;
      if (o.value === preferred) opt.dataset.preferred = '';
      select.append(opt);
      map.set(o.value, o.data);
    }
    this.sources.set(path, map);
    select.selectedIndex = preferredIndex(select);
    this.syncToggles();
  }

  sourceValue(path) {
    const select = this.form.querySelector(`[data-source="${path}"]`);
    return select ? this.sources.get(path)?.get(select.value) : undefined;
  }

  // A loaded block selects the source it came from; a block with other data
  // gets an option of its own, so running it sends what was loaded.
  matchSource(path, block) {
    const select = this.form.querySelector(`[data-source="${path}"]`);
    const map = this.sources.get(path) || new Map();
    if (!select) return;
    const same = (data) => Object.keys(data).every((k) => JSON.stringify(data[k]) === JSON.stringify(block[k]));
    for (const [value, data] of map) {
      if (same(data)) { select.value = value; return; }
    }
    const keys = map.size ? Object.keys(map.values().next().value) : Object.keys(block).filter((k) => Array.isArray(block[k]));
    if (!keys.some((k) => k in block)) return;
    const data = Object.fromEntries(keys.filter((k) => k in block).map((k) => [k, block[k]]));
    const value = 'loaded scene';
    map.set(value, data);
    this.sources.set(path, map);
    let opt = [...select.options].find((o) => o.value === value);
    if (!opt) {
      opt = document.createElement('option');
      opt.value = value;
      opt.textContent = 'the loaded scene';
      select.append(opt);
    }
    select.value = value;
  }

  // ---- repeated templates ----------------------------------------------

  // `count` copies of the template of a [data-each], its fields at their
  // defaults.
  setCopies(each, count) {
    const template = each.querySelector('template');
    for (const copy of [...each.children]) if (copy !== template) copy.remove();
    for (let i = 0; i < count; i++) {
      const copy = template.content.cloneNode(true);
      const fill = (t) => t.replaceAll('{i}', String(i)).replaceAll('{n}', String(i + 1));
      for (const el of copy.querySelectorAll('*')) {
        for (const a of el.attributes) if (/\{[in]\}/.test(a.value)) a.value = fill(a.value);
      }
      const walker = document.createTreeWalker(copy, NodeFilter.SHOW_TEXT);
      for (let n = walker.nextNode(); n; n = walker.nextNode()) if (n.data.includes('{n}')) n.data = fill(n.data);
      for (const input of copy.querySelectorAll('[data-path]')) {
        setValue(input, input.dataset.default);
        if (input.dataset.hint) this.addHint(input);
      }
      each.append(copy);
    }
  }

  // ---- editable lists --------------------------------------------------

  // One click handler for every list's add and remove buttons, also those of
  // the lists in rows added later.
  setupLists() {
    this.form.addEventListener('click', (e) => {
      const add = e.target.closest('[data-list-add]');
      const remove = e.target.closest('[data-list-remove]');
      const list = (add || remove)?.closest('[data-list]');
      if (!list) return;
      if (add) {
        const row = this.addRow(list, {}, true);
        own(list, row, '[data-field]:is(input, select)')[0]?.focus();
      } else {
        const row = rowsOf(list).find((r) => r.contains(remove));
        if (!row) return;
        const next = row.nextElementSibling || row.previousElementSibling;
        row.remove();
        this.numberRows(list);
        // Keep the keyboard focus in the list.
        ((next && own(list, next, '[data-list-remove]')[0]) || own(list, list, '[data-list-add]')[0])?.focus();
      }
      this.syncWhens();
      this.changed();
    });
  }

  // A new row with the template's defaults, or with `values` ({field: v};
  // a row's own list: its array of rows).  `added`: by the add button (a
  // data-next field continues from the row before).
  addRow(list, values = {}, added = false) {
    const template = own(list, list, 'template')[0];
    const row = template.content.firstElementChild.cloneNode(true);
    const before = rowsOf(list).at(-1);
    rowBox(list).append(row);
    const inputs = own(list, row, '[data-field]:is(input, select)');
    for (const input of inputs) {
      const v = values[input.dataset.field];
      const prev = added && before && input.dataset.next !== undefined
        ? own(list, before, `[data-field="${input.dataset.field}"]`)[0]?.valueAsNumber : NaN;
      if (v !== undefined && v !== null && typeof v !== 'object') setValue(input, v);
      else if (Number.isFinite(prev)) setValue(input, Number((prev + Number(input.dataset.next)).toPrecision(12)));
      else setValue(input, input.dataset.default);
      if (input.dataset.hint) this.addHint(input); // its id is set by numberRows
    }
    for (const inner of innerLists(list, row)) {
      const rows = values[inner.dataset.field];
      this.setRows(inner, Array.isArray(rows) ? rows : []);
    }
    this.numberRows(list);
    for (const input of row.querySelectorAll('[data-field]')) this.updateHint(input);
    return row;
  }

  setRows(list, rows) {
    rowBox(list).replaceChildren();
    for (const r of rows) this.addRow(list, r && typeof r === 'object' ? r : {});
    this.numberRows(list);
  }

  // The rows of a list as the scene takes them (throws as read() does);
  // a row's own list goes in at its key when it has rows.
  readList(list) {
    return rowsOf(list).map((row) => {
      const out = {};
      for (const input of own(list, row, '[data-field]:is(input, select)')) {
        const v = readValue(input);
        if (v !== undefined) out[input.dataset.field] = v;
      }
      for (const inner of innerLists(list, row)) {
        const rows = this.readList(inner);
        if (rows.length) out[inner.dataset.field] = rows;
      }
      return out;
    });
  }

  // Row i's inputs get id, data-path (/list/i/field) and their labels
  // "… {n}" = i + 1; a row's own lists their path (/list/i/key) and numbers.
  numberRows(list) {
    const rows = rowsOf(list);
    const p = list.dataset.parentN ?? '';
    const text = (el, n) => {
      const t = el.dataset.label.replaceAll('{n}', n).replaceAll('{p}', p);
      if (el.tagName === 'BUTTON') el.setAttribute('aria-label', t);
      else el.textContent = t;
    };
    rows.forEach((row, i) => {
      for (const input of own(list, row, '[data-field]:is(input, select)')) {
        const label = input.parentElement.querySelector('label');
        const hint = input.parentElement.querySelector('.unit-hint');
        input.id = `${list.id}-${i}-${input.dataset.field}`;
        input.dataset.path = `${list.dataset.list}/${i}/${input.dataset.field}`;
        if (label) label.htmlFor = input.id;
        if (hint) {
          hint.id = `${input.id}-hint`;
          input.setAttribute('aria-describedby', hint.id);
        }
      }
      for (const el of own(list, row, '[data-label]')) text(el, String(i + 1));
      const head = own(list, row, '[data-row-head]')[0];
      if (head) {
        head.id = `${list.id}-${i}-head`;
        row.setAttribute('aria-labelledby', head.id);
      }
      for (const inner of innerLists(list, row)) {
        inner.id = `${list.id}-${i}-${inner.dataset.field}`;
        inner.dataset.list = `${list.dataset.list}/${i}/${inner.dataset.field}`;
        inner.dataset.parentN = String(i + 1);
        this.numberRows(inner);
      }
    });
    for (const el of own(list, list, '[data-label]')) if (!rows.some((r) => r.contains(el))) text(el, '');
    this.syncListButtons(list);
    const max = Number(list.dataset.max) || Infinity;
    const count = own(list, list, '[data-list-count]').find((c) => !rows.some((r) => r.contains(c)));
    if (count) count.textContent = `${rows.length} of ${Number.isFinite(max) ? max : 'any'} ${list.dataset.unit || 'rows'}`;
  }

  // The add button: off at data-max rows, and while the list does not count.
  syncListButtons(list) {
    const max = Number(list.dataset.max) || Infinity;
    const rows = rowsOf(list);
    const add = own(list, list, '[data-list-add]').find((b) => !rows.some((r) => r.contains(b)));
    if (add) add.disabled = rows.length >= max || this.isOff(list);
  }

  // ---- errors ------------------------------------------------------------

  // The inputs an error path points at: the exact field, else the fields
  // below it ("/ring/material"), else the nearest field above it.  Only the
  // fields of the shown analysis count (two analyses may share a path).
  fieldsFor(path) {
    if (!path) return [];
    const inputs = this.analysis ? this.inputsFor(this.analysis) : this.inputs;
    const at = (i) => (this.analysis ? this.pathsOf(i, this.analysis) : [pathOf(i)]);
    const exact = inputs.filter((i) => at(i).includes(path));
    if (exact.length) return exact;
    const below = inputs.filter((i) => at(i).some((p) => p.startsWith(`${path}/`)));
    if (below.length) return below;
    const longest = (i) => Math.max(...at(i).filter((p) => path.startsWith(`${p}/`)).map((p) => p.length));
    const above = inputs
      .filter((i) => at(i).some((p) => path.startsWith(`${p}/`)))
      .sort((a, b) => longest(b) - longest(a));
    return above.slice(0, 1);
  }

  // What to call a group of fields from fieldsFor(): the field's label, or
  // for several fields their fieldset's legend.
  nameOf(fields) {
    const text = (el) => el?.textContent.replace(/\s+/g, ' ').trim();
    if (fields.length > 1) return text(fields[0].closest('fieldset')?.querySelector('legend')) || pathOf(fields[0]);
    return text(this.form.querySelector(`label[for="${fields[0].id}"]`)) || pathOf(fields[0]);
  }

  // Highlights the fields of an error path; returns them (the first one
  // focused unless `focus` is false).
  mark(path, errorId, focus = true) {
    const fields = this.fieldsFor(path);
    for (const input of fields) {
      input.setAttribute('aria-invalid', 'true');
      input.setAttribute('aria-errormessage', errorId);
      (input.closest('.field') || input.closest('td'))?.classList.add('invalid');
    }
    // Centred, so the sticky run bar (which shows the message) does not cover it.
    if (focus) {
      fields[0]?.focus({ preventScroll: true });
      fields[0]?.scrollIntoView({ block: 'center' });
    }
    return fields;
  }

  unmark(input) {
    input.removeAttribute('aria-invalid');
    input.removeAttribute('aria-errormessage');
    (input.closest('.field') || input.closest('td'))?.classList.remove('invalid');
  }

  clearMarks() {
    for (const input of this.inputs) this.unmark(input);
  }
}

// Shared inputs (outside any analysis fieldset) belong to every analysis.
function ownedBy(el, analysis) {
  const owner = el.closest('[data-analysis]');
  return !owner || owner.dataset.analysis === analysis;
}

// Whether a [data-when]'s <select> has one of its data-when-in values (a
// list's value: "rows" or "none").
function whenHolds(when) {
  const el = document.getElementById(when.dataset.when);
  if (!el) return false;
  const value = el.matches('[data-list]') ? (rowsOf(el).length ? 'rows' : 'none') : el.value;
  return (when.dataset.whenIn || '').split(/\s+/).includes(value);
}

// ---- list rows ---------------------------------------------------------

// Where a list's rows are: its [data-rows] element or its table's <tbody>
// (not those of a list in one of its rows).
function rowBox(list) {
  return [...list.querySelectorAll('[data-rows], tbody')].find((b) => b.closest('[data-list]') === list);
}

function rowsOf(list) {
  const box = rowBox(list);
  return box ? [...box.children] : [];
}

// The elements below `root` matching `sel` that belong to `list` itself,
// not to a list in one of its rows.
function own(list, root, sel) {
  return [...root.querySelectorAll(sel)].filter((el) => el.closest('[data-list]') === list);
}

// The lists of a row of `list`.
function innerLists(list, row) {
  return [...row.querySelectorAll('[data-list]')].filter((l) => l.parentElement.closest('[data-list]') === list);
}

// Deletes the members of `value` that `schema` (OpenAPI, resolved by
// `resolve`) does not list, at every depth.
function prune(value, schema, resolve) {
  const s = resolve(schema);
  if (Array.isArray(value)) {
    if (s?.items) for (const v of value) prune(v, s.items, resolve);
    return;
  }
  if (value === null || typeof value !== 'object' || !s?.properties) return;
  for (const key of Object.keys(value)) {
    if (key in s.properties) prune(value[key], s.properties[key], resolve);
    else delete value[key];
  }
}

function preferredIndex(select) {
  const i = [...select.options].findIndex((o) => 'preferred' in o.dataset);
  return i >= 0 ? i : 0;
}

// One field's scene value (see the encoding above); undefined = leave it out.
function readValue(input) {
  const word = input.id ? document.querySelector(`[data-word-for="${input.id}"]`) : null;
  if (word?.checked) return word.dataset.word;
  if (input.type === 'checkbox') return input.checked;
  if (input.tagName === 'SELECT') return input.value;
  if (input.dataset.word !== undefined) return wordOrNumber(input);
  if (input.value === '' && !input.validity.badInput) {
    if ('optional' in input.dataset && !input.required) return undefined;
    throw { code: 'invalid_value', message: 'must be a number (it is empty)', path: input.dataset.path };
  }
  const v = input.valueAsNumber;
  if (!Number.isFinite(v)) {
    throw { code: 'invalid_value', message: 'must be a number', path: input.dataset.path };
  }
  if (input.dataset.type === 'int' && !Number.isInteger(v)) {
    throw { code: 'invalid_value', message: `must be a whole number, got ${v}`, path: input.dataset.path };
  }
  return v;
}

// A text input that takes a number or its one word (data-word).
function wordOrNumber(input) {
  const t = input.value.trim(), word = input.dataset.word;
  if (t === word) return word;
  const v = t === '' ? NaN : Number(t);
  if (!Number.isFinite(v)) {
    throw { code: 'invalid_value', message: `must be a number or "${word}"`, path: input.dataset.path };
  }
  return v;
}

function setValue(input, v) {
  if (input.type === 'checkbox') input.checked = v === true || v === 'true';
  else if (input.tagName === 'SELECT') input.value = v === undefined ? input.options[0]?.value ?? '' : String(v);
  else input.value = v === undefined ? '' : numberText(v);
}

// A number as a field shows it whole: very large or small ones in exponent
// form (2.1e11, not 210000000000, which a narrow field cuts off).
function numberText(v) {
  if (typeof v !== 'number' || !Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  return a === 0 || (a >= 1e-4 && a < 1e7) ? String(v) : v.toExponential().replace('e+', 'e');
}

// A default as a person writes it: 2.1e11 and 3e-5, not 210000000000 and 0.00003.
function formatDefault(v) {
  const a = Math.abs(v);
  return a !== 0 && (a >= 1e6 || a < 1e-4) ? v.toExponential().replace('e+', 'e') : String(v);
}

// JSON Pointer (RFC 6901) get / set / delete on plain objects.
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
  ts.slice(0, -1).forEach((t, i) => {
    if (typeof cur[t] !== 'object' || cur[t] === null) cur[t] = /^\d+$/.test(ts[i + 1]) ? [] : {};
    cur = cur[t];
  });
  cur[ts[ts.length - 1]] = value;
}

// Removes the field; a parent object left empty is removed too, so an
// unchecked toggle does not leave "physics": {} behind.
function pointerDelete(obj, path) {
  const ts = tokens(path);
  const chain = [obj];
  for (const t of ts.slice(0, -1)) {
    const next = chain[chain.length - 1][t];
    if (next === null || typeof next !== 'object') return;
    chain.push(next);
  }
  delete chain[chain.length - 1][ts[ts.length - 1]];
  for (let i = chain.length - 1; i > 0; i--) {
    if (Object.keys(chain[i]).length) break;
    delete chain[i - 1][ts[i - 1]];
  }
}
