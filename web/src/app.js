// The oscidrum explorer page: inputs (keys, units, defaults and rules from the engine's field
// table), a Web Worker that runs the engine, plots, the drum animation, metrics, URL state and
// exports. Plain ES module; the plots of time series and spectra use uPlot.
import uPlot from './vendor/uPlot.esm.js';

const $ = (id) => document.getElementById(id);
const COLORS = { x: '#1f5fa8', z: '#c23b22', measured: '#111', stick: '#cdeccd', slipp: '#ffd9a8', slipn: '#f7c1c1', flight: '#ddd0f2' };
const ARROW = { stick: '#1d7a1d', slip: '#d46a00', flight: '#7a5cc4' };
const ROTATION_FACTOR = 100;     // the drum's rotation phi is drawn this many times larger
const DISPLACEMENT_FACTOR = 50;  // the soil displacements x_A, s_A are drawn this many times larger
const N_MAX = 10;                // harmonics n = 0 ... N_MAX
const F_REF = 39;                // [Hz] the frequency of the paper's M0 (Table 1)

// The inputs of the page. `key`: the field of the engine (default, unit, rule and the unit shown
// come from there: the field's display_unit and display_scale, e.g. MN/m^2 for soil.G, replace
// `unit` and `scale` when the engine is ready); `scale`: displayed value = SI value / scale.
const INPUTS = {
  G: { key: 'soil.G', label: 'G', hint: 'shear modulus' },
  nu: { key: 'soil.nu', label: 'ν', unit: '-', scale: 1 },
  rho: { key: 'soil.rho', label: 'ρ', unit: 'kg/m³', scale: 1 },
  mu: { key: 'contact.mu', label: 'μ', unit: '-', scale: 1 },
  f: { key: 'roller.f', label: 'f', unit: 'Hz', scale: 1 },
  M0: { key: 'roller.M0', label: 'M0', unit: 'N m', scale: 1 },
  // the driving torque as a fraction of M0 (shown where roller.M0 takes effect: the oscillation
  // drum), and in N m where it does not (the vibratory drum, whose excitation is a force)
  MMd: { key: null, ref: 'roller.M0', label: 'MMd', unit: '× M0', scale: 1, hint: 'driving torque (6), a fraction of M0; the paper uses 0 and 0.05' },
  static_moment: { key: 'roller.static_moment', label: 'm<sub>u</sub>e<sub>u</sub>', param: 'roller.static_moment' },
  exciter: { key: 'roller.exciter', label: 'exciter', param: 'roller.exciter' },
  torque: { key: 'MMd', unlessRef: 'roller.M0', label: 'MMd', unit: 'N m', scale: 1, hint: 'constant driving torque (6)' },
  R: { key: 'trough.a', label: 'R', unit: 'm', scale: 1, hint: 'trough radius (must exceed the drum radius r)' },
  k: { key: 'trough.k', label: 'k', unit: '-', scale: 1 },
  a: { key: 'trough.a', label: 'a', unit: 'm', scale: 1 },
  kd: { key: 'roller.kd', label: 'kd', unit: 'N/m', scale: 1 },
  cd: { key: 'roller.cd', label: 'cd', unit: 'N s/m', scale: 1 },
};

// The rollers of the field roller.type, in words: the selector's options, the page's title and
// introduction, a note under the selector. Which inputs each roller takes is the engine's
// key_in_effect (rollerKeys, from the worker), not written here. `preset`: the inputs a roller
// starts with when it is chosen, where they differ from the page's defaults (the field table's);
// the vibratory drum's are those of examples/vibratory.toml (the e2e test runs that file).
const ROLLERS = {
  oscillation: {
    option: "oscillation drum (the paper's HAMM HD+ 90 VO)",
    title: 'the oscillation drum',
    intro: 'The oscillation roller drum on soil of Paulmichl, Adam &amp; Adam, <i>Analytical modeling of the ' +
      'stick-slip motion of an oscillation drum</i>, Acta Mechanica 230 (2019)',
    note: 'Two counter-rotating unbalances turn the drum to and fro with the moment M0 sin(ν t) (5): the paper\'s roller (Table 1).',
    preset: {},
  },
  vibratory: {
    option: 'vibratory drum (a rotating unbalance)',
    title: 'the vibratory drum',
    intro: 'A vibratory roller drum: the drum of Paulmichl, Adam &amp; Adam (Acta Mechanica 230, 2019) with one ' +
      'unbalance turning on its axis, whose force m_u e_u ν² pulls on the drum centre (oscidrum docs/model.md section 14), ' +
      'on the same buffers, soils and trough',
    note: 'An unbalance turning on the axis of the paper\'s drum pulls on its centre with the force F0 = m_u e_u ν², ' +
      'in the direction the exciter gives (docs/vibratory.md). It starts as examples/vibratory.toml: 0.9 kg m at 30 Hz, ' +
      'circular, with contact that can open (contact.unilateral, under more parameters).',
    preset: { f: '30', 'contact.unilateral': true },
  },
};
// The page's defaults of inputs whose field default is not one: no driving torque (MMd given as a
// fraction of M0), and the vibratory drum's static moment of examples/vibratory.toml (the field's
// default 0 is refused with roller.type = vibratory).
const PAGE_DEFAULTS = { MMd: '0', torque: '0', static_moment: '0.9' };
// The inputs of the roller's excitation: set to the roller's defaults when the roller is chosen.
const ROLLER_INPUTS = ['f', 'M0', 'MMd', 'static_moment', 'exciter', 'torque'];

let fields = [];            // the engine's field table
let extras = [];            // the fields without an input above ('more parameters'), by key
// The keys the inputs above set (the rest of the field table is under 'more parameters').
const COVERED = new Set(['soil.input', 'soil.G', 'soil.nu', 'soil.rho', 'soil.ksh', 'soil.ksv', 'soil.csh',
  'soil.csv', 'contact.mu', 'contact.pure_rolling', 'roller.f', 'roller.M0', 'MMd', 'trough.k', 'trough.a',
  'roller.kd', 'roller.cd', 'roller.type', 'roller.static_moment', 'roller.exciter']);
const extraName = (key) => `x:${key}`;
let fieldByKey = {};
let soilKeys = {};          // soil.input name -> the soil keys it reads (the engine's key_in_effect)
let rollerKeys = {};        // roller.type name -> the keys of that roller only (key_in_effect)
let worker = null;
let seq = 0;                // number of the latest request
let busySince = 0;          // time the running request was sent (0: idle)
let pending = null;         // the latest request not yet sent
let last = null;            // the latest good result {result, values, ms}
let inputErrors = {};       // the latest messages of the page's own parsing, by input name
const plots = {};

// ---------------------------------------------------------------- inputs

function fmt(x, digits = 6) {
  if (!Number.isFinite(x)) return String(x);
  return Number(x.toPrecision(digits)).toString();
}

// 'MN/m^2' -> 'MN/m²'
const prettyUnit = (unit) => unit.replace(/\^2/g, '²').replace(/\^3/g, '³');

function buildInputs() {
  for (const spec of Object.values(INPUTS)) {
    const field = spec.key ? fieldByKey[spec.key] : null;
    if (field && spec.scale === undefined) {
      spec.unit = prettyUnit(field.display_unit);
      spec.scale = field.display_scale;
    }
  }
  // the roller selector: the choices of roller.type
  $('roller_type').innerHTML = fieldByKey['roller.type'].choices
    .map((c) => `<option value="${c}">${(ROLLERS[c] || { option: c }).option}</option>`).join('');
  for (const div of document.querySelectorAll('.field[data-input]')) {
    const name = div.dataset.input;
    const spec = INPUTS[name];
    const field = spec.key ? fieldByKey[spec.key] : null;
    const desc = spec.hint || (field ? field.description : '');
    const rule = field ? `rule: ${ruleIn(field, spec)}` : 'any finite number';
    const control = field && field.type === 'choice'
      ? `<select id="in-${name}" name="${name}">${field.choices.map((c, i) => `<option value="${i}">${c}</option>`).join('')}</select>`
      : `<input type="text" inputmode="decimal" id="in-${name}" name="${name}" aria-describedby="err-${name}">`;
    div.innerHTML = `<label><span class="name">${spec.label}</span>${control}` +
      `<span class="unit">${spec.unit === '-' ? '' : spec.unit}</span></label>` +
      `<span class="hint">${desc}${field ? ' (' + field.key + '; ' + rule + ')' : ''}</span>` +
      `<span class="error" id="err-${name}" role="alert"></span>`;
    setInputText(name, defaultText(name));
  }
  // every other field of the table, with its default, unit and rule
  extras = fields.filter((f) => !COVERED.has(f.key));
  const box = $('more-fields');
  for (const f of extras) {
    const name = extraName(f.key);
    const div = document.createElement('div');
    div.className = 'field';
    div.dataset.input = name;
    let control;
    if (f.type === 'boolean') control = `<input type="checkbox" id="in-${name}" name="${f.key}">`;
    else if (f.type === 'choice') control = `<select id="in-${name}" name="${f.key}">${f.choices.map((c, i) => `<option value="${i}">${c}</option>`).join('')}</select>`;
    else control = `<input type="text" inputmode="decimal" id="in-${name}" name="${f.key}">`;
    div.innerHTML = `<label><span class="name wide">${f.key}</span>${control}<span class="unit">${f.unit}</span></label>` +
      `<span class="hint">${f.description} (rule: ${f.rule})</span><span class="error" id="err-${name}" role="alert"></span>`;
    box.appendChild(div);
    setExtra(f, f.default);
  }
}

// A field's rule with its unit, e.g. '>= 0 kg m'.
const ruleText = (field) => `${field.rule}${field.unit !== '-' ? ' ' + field.unit : ''}`;

// The rule in the unit an input reads its value in (MN/m^2 for soil.G: the engine's rule is in
// Pa, which the box labelled MN/m² showed beside it).
function ruleIn(field, spec) {
  if (!spec || !spec.scale || spec.scale === 1 || !Number.isFinite(field.min) || !Number.isFinite(field.max))
    return ruleText(field);
  const lo = field.min_open ? '(' : '[', hi = field.max_open ? ')' : ']';
  return `in ${lo}${fmt(field.min / spec.scale)}, ${fmt(field.max / spec.scale)}${hi} ${spec.unit}`;
}

// The engine's message about an input's field, in the input's unit: "soil.G must be in [10000,
// 1e+11] [Pa]; got 1000 (values are in Pa: did you mean ...)" stood beside a box where 0.001
// MN/m² had been typed.
function inputMessage(name, message) {
  const spec = INPUTS[name];
  const field = spec && spec.key ? fieldByKey[spec.key] : null;
  // (only the field's own rule: "soil.G must be a G of paper Table 2" stays as it is)
  if (!field || !spec.scale || spec.scale === 1 || !message.startsWith(`${field.key} must be ${field.rule}`)) return message;
  return `${field.key} must be ${ruleIn(field, spec)}; got ${inputText(name)} ${spec.unit}`;
}

// The index of a choice given by its name or its index ('vibratory' or '1'), or -1.
function choiceIndex(field, text) {
  const i = field.choices.indexOf(String(text));
  if (i >= 0) return i;
  return /^\d+$/.test(String(text)) && Number(text) < field.choices.length ? Number(text) : -1;
}

// Set an extra field's control from a value or text (a choice by its name or index, a boolean as
// true/false).
function setExtra(f, value) {
  const el = $(`in-${extraName(f.key)}`);
  if (f.type === 'boolean') el.checked = value === true || value === 1 || value === 'true' || value === '1';
  else if (f.type === 'choice') el.value = String(Math.max(0, choiceIndex(f, value)));
  else el.value = String(value);
}

// The text of an extra field's control ('true'/'false' for booleans, a choice's name).
function extraText(f) {
  const el = $(`in-${extraName(f.key)}`);
  if (f.type === 'boolean') return String(el.checked);
  if (f.type === 'choice') return f.choices[Number(el.value)] ?? el.value;
  return el.value.trim();
}

// The default of an extra field with the roller `roller` (its preset, else the field table's).
function extraDefault(f, roller = currentRoller()) {
  const preset = (ROLLERS[roller] || { preset: {} }).preset;
  return f.key in preset ? preset[f.key] : f.default;
}

function extraDefaultText(f, roller = currentRoller()) {
  const v = extraDefault(f, roller);
  if (f.type === 'boolean') return String(v === true || v === 1);
  if (f.type === 'choice') return f.choices[v] ?? String(v);
  return String(v);
}

// The default text of an input with the roller `roller`: its preset, the page's default, the
// field table's (a choice by its name).
function defaultText(name, roller = currentRoller()) {
  const preset = (ROLLERS[roller] || { preset: {} }).preset;
  if (name in preset) return preset[name];
  if (name in PAGE_DEFAULTS) return PAGE_DEFAULTS[name];
  const spec = INPUTS[name];
  const field = fieldByKey[spec.key];
  if (field.type === 'choice') return field.choices[field.default];
  return fmt(field.default / spec.scale, 10);
}

// The text of an input (a choice by its name), and setting it from such a text.
function inputText(name) {
  const el = $(`in-${name}`);
  const field = INPUTS[name].key ? fieldByKey[INPUTS[name].key] : null;
  if (field && field.type === 'choice') return field.choices[Number(el.value)] ?? el.value;
  return el.value.trim();
}

function setInputText(name, text) {
  const el = $(`in-${name}`);
  const field = INPUTS[name].key ? fieldByKey[INPUTS[name].key] : null;
  if (field && field.type === 'choice') el.value = String(Math.max(0, choiceIndex(field, text)));
  else el.value = text;
}

// ---- the roller

// The chosen roller (a name of roller.type's choices).
const currentRoller = () => $('roller_type').value || fieldByKey['roller.type'].choices[0];

// Whether the key takes effect with the chosen roller: the keys of one roller only (rollerKeys,
// the engine's key_in_effect) with that roller; every other key.
function rollerKeyInEffect(key, roller = currentRoller()) {
  const own = Object.values(rollerKeys).some((keys) => keys.includes(key));
  return !own || (rollerKeys[roller] || []).includes(key);
}

// Whether an input applies to the chosen roller: by the key it sets (or is a fraction of: MMd of
// roller.M0), or, for the driving torque in N m, where the fraction of M0 does not.
function rollerInput(name) {
  const spec = INPUTS[name];
  if (spec.unlessRef) return !rollerKeyInEffect(spec.unlessRef);
  const key = spec.ref || spec.key;
  return !key || rollerKeyInEffect(key);
}

// Choosing a roller starts it from its defaults: the inputs of its excitation (f, M0, MMd; the
// static moment, the exciter) and its preset (the vibratory drum: 30 Hz, contact that can open);
// the soil, the contact's mu, the trough and the suspension stay as they are.
let appliedRoller = null;
function applyRoller(roller) {
  if (roller === appliedRoller) return;
  appliedRoller = roller;
  for (const name of ROLLER_INPUTS) setInputText(name, defaultText(name, roller));
  $('M0_scale').checked = false;
  // the extra fields some roller presets (contact.unilateral) or only one roller takes
  const preset = (key) => Object.values(ROLLERS).some((r) => key in r.preset);
  for (const f of extras) {
    if (preset(f.key) || Object.values(rollerKeys).some((keys) => keys.includes(f.key))) setExtra(f, extraDefault(f, roller));
  }
}

// The title, introduction and notes of the chosen roller.
let shownRoller = null;
function showRoller() {
  const roller = currentRoller();
  if (roller === shownRoller) return;
  shownRoller = roller;
  const words = ROLLERS[roller] || { title: `the ${roller} drum`, intro: `The ${roller} drum`, note: '' };
  $('roller-title').textContent = words.title;
  $('roller-intro').innerHTML = words.intro;
  $('roller-note').textContent = words.note;
  document.title = `oscidrum explorer: ${words.title.replace(/^the /, '')} on soil`;
  $('metrics-note').innerHTML = roller === 'vibratory'
    ? 'Definitions (peaks, harmonics A<sub>n</sub> sin(n 2&pi;f t + &theta;<sub>n</sub>), the CMV-type value 300 A<sub>2</sub>/A<sub>1</sub> ' +
      'and the RMV-type value A(f/2)/A(f) of z<sub>M</sub>\'\', the Kb-type soil stiffness kb, the operating modes, the area) are those of ' +
      'the oscidrum command-line tool; see docs/outputs.md and docs/model.md section 14. Required mu is the largest |T| / N of the steady state.'
    : 'Definitions (peaks, harmonics A<sub>n</sub> sin(n 2&pi;f t + &theta;<sub>n</sub>), the lag of &phi; behind the torque, the ' +
      'x<sub>M</sub>\'\'-to-z<sub>M</sub>\'\' lag, the area counting both lobes of a figure-eight) are those of the oscidrum command-line ' +
      'tool; see docs/model.md. Required mu is the largest |T| / N of the steady state.';
}

function setError(name, message) {
  const div = document.querySelector(`.field[data-input="${name}"]`);
  div.classList.toggle('invalid', Boolean(message));
  $(`err-${name}`).textContent = message || '';
}

// The soil inputs (G, nu, rho) the chosen soil.input reads, by the engine's key_in_effect.
const SOIL_INPUTS = ['G', 'nu', 'rho'];
function soilInputInEffect(name) {
  return (soilKeys[$('soil_mode').value] || []).includes(INPUTS[name].key);
}

// The extra fields ('more parameters') that apply to the chosen roller.
const rollerExtras = () => extras.filter((f) => rollerKeyInEffect(f.key));

function visibleInputs() {
  const spiral = $('trough_mode').value === 'spiral';
  const names = ['mu', ...ROLLER_INPUTS.filter(rollerInput), 'kd', 'cd'];
  names.unshift(...SOIL_INPUTS.filter(soilInputInEffect));
  names.push(...(spiral ? ['k', 'a'] : ['R']));
  if ($('rolling').checked) names.splice(names.indexOf('mu'), 1);
  // an unbalance sets M0 (5): the (disabled) M0 box is then neither read nor checked
  if (names.includes('M0') && unbalanceInput() > 0) names.splice(names.indexOf('M0'), 1);
  for (const f of rollerExtras()) names.push(extraName(f.key));
  return names;
}

function updateVisibility() {
  showRoller();
  const spiral = $('trough_mode').value === 'spiral';
  for (const name of SOIL_INPUTS) document.querySelector(`.field[data-input="${name}"]`).hidden = !soilInputInEffect(name);
  for (const el of document.querySelectorAll('.spiral-only')) el.hidden = !spiral;
  for (const el of document.querySelectorAll('.circle-only')) el.hidden = spiral;
  // the inputs of the other roller are hidden (and not sent to the engine)
  for (const name of ROLLER_INPUTS) document.querySelector(`.field[data-input="${name}"]`).hidden = !rollerInput(name);
  $('M0_scale_box').hidden = !rollerInput('M0');
  // An unbalance sets M0 (5): the M0 input and its f^2 box then say so and are not used.
  const byUnbalance = unbalanceInput() > 0;
  $('in-M0').disabled = byUnbalance;
  $('M0_scale').disabled = byUnbalance;
  $('in-M0').title = byUnbalance ? 'not used: roller.unbalance sets M0 = 4 m_u e_u e_w ν² (5)' : '';
  for (const f of extras) document.querySelector(`.field[data-input="${extraName(f.key)}"]`).hidden = !rollerKeyInEffect(f.key);
  $('in-mu').disabled = $('rolling').checked;
  const scaled = $('M0_scale').checked;
  document.querySelector('.field[data-input="M0"] .name').textContent = scaled ? 'M0(39 Hz)' : 'M0';
  const unilateral = $(`in-${extraName('contact.unilateral')}`);
  $('flight-key').hidden = !(unilateral && unilateral.checked);
}

// Parse the visible inputs. Returns {values, errors}: values (display units) by input name,
// errors (messages) by input name for empty, non-numeric or non-finite text (the rules of the
// values, a G that Table 2 does not hold included, are the engine's).
function readInputs() {
  const values = {};
  const errors = {};
  for (const name of visibleInputs()) {
    const f = name.startsWith('x:') ? fieldByKey[name.slice(2)] : null;
    if (f && f.type === 'boolean') {
      values[name] = $(`in-${name}`).checked ? 1 : 0;
      continue;
    }
    const text = $(`in-${name}`).value.trim();
    // The message names the field and its rule (the unit the input is read in where it differs).
    const field = f || (INPUTS[name] && INPUTS[name].key ? fieldByKey[INPUTS[name].key] : null);
    const spec = INPUTS[name];
    const shownIn = spec && spec.unit && field && prettyUnit(field.unit) !== spec.unit && spec.unit !== '-' ? `, entered in ${spec.unit}` : '';
    const about = field ? `${field.key} (rule: ${ruleIn(field, spec)}${shownIn})` : `${spec.label} (any finite number${spec.unit ? ', ' + spec.unit : ''})`;
    if (text === '') {
      errors[name] = `enter a value: ${about}`;
      continue;
    }
    const v = decimalNumber(text);
    // An integer key takes digits only, as in a case file and --set (5.0 and 1e3 are refused).
    if (field && field.type === 'integer' && !/^[+-]?\d+$/.test(text)) errors[name] = `not an integer (digits only): '${text}'; ${about}`;
    else if (Number.isNaN(v)) errors[name] = `not a number: '${text}'; ${about}`;
    else if (!Number.isFinite(v)) errors[name] = `must be finite; ${about}`;
    else values[name] = v;
  }
  return { values, errors };
}

// A decimal number's value (NaN for any other text), as the command line reads numbers:
// Number() also took 0x28, 0b1 and 0o50.
function decimalNumber(text) {
  const t = String(text).trim();
  if (/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(t)) return Number(t);
  if (/^[+-]?(inf|infinity)$/i.test(t)) return t.startsWith('-') ? -Infinity : Infinity;
  return NaN;
}

// M0 = 4 m_u e_u e_w nu^2 (5) of an unbalance m_u e_u e_w [kg m^2] at f [Hz].
const oscillationMoment = (unbalance, f) => 4 * unbalance * (2 * Math.PI * f) ** 2;

// The unbalance the inputs give (0 without one): the M0 input is then not in effect.
function unbalanceInput() {
  if (!fieldByKey['roller.unbalance'] || !rollerKeyInEffect('roller.unbalance')) return 0;
  const u = decimalNumber(extraText(fieldByKey['roller.unbalance']));
  return Number.isFinite(u) && u > 0 ? u : 0;
}

// The engine's case (field key -> SI number) from the parsed inputs.
function caseValues(v) {
  const shown = new Set(visibleInputs());
  // The roller; the soil: its input (the engine converts it, Table 2 or Appendix B) and the keys
  // it reads.
  const c = { 'roller.type': fieldByKey['roller.type'].choices.indexOf(currentRoller()) };
  c['soil.input'] = fieldByKey['soil.input'].choices.indexOf($('soil_mode').value);
  for (const name of SOIL_INPUTS.filter(soilInputInEffect)) c[INPUTS[name].key] = v[name] * INPUTS[name].scale;
  if ($('rolling').checked) c['contact.pure_rolling'] = 1;
  else c['contact.mu'] = v.mu;
  c['roller.f'] = v.f;
  // The excitation of the chosen roller (the other roller's inputs are not sent): the oscillation
  // drum's M0 (M0 = 4 m_u e_u e_w nu^2 grows with f^2 (5)) and MMd as its fraction; the vibratory
  // drum's static moment, exciter and MMd in N m.
  // With roller.unbalance the engine takes M0 = 4 m_u e_u e_w nu^2 (5) and the M0 input is not
  // in effect (oscidrum run refuses both): MMd is a fraction of that M0, as --MMd-fraction is.
  const unbalance = shown.has(extraName('roller.unbalance')) ? v[extraName('roller.unbalance')] : 0;
  const M0 = unbalance > 0 ? oscillationMoment(unbalance, v.f)
    : $('M0_scale').checked ? v.M0 * (v.f / F_REF) ** 2 : v.M0;
  if (shown.has('M0') && !(unbalance > 0)) c['roller.M0'] = M0;
  if (shown.has('MMd')) c.MMd = v.MMd * M0;
  if (shown.has('static_moment')) c['roller.static_moment'] = v.static_moment;
  if (shown.has('exciter')) c['roller.exciter'] = v.exciter;
  if (shown.has('torque')) c.MMd = v.torque;
  if ($('trough_mode').value === 'spiral') {
    c['trough.k'] = v.k;
    c['trough.a'] = v.a;
  } else {
    c['trough.k'] = 0;
    c['trough.a'] = v.R;
  }
  c['roller.kd'] = v.kd;
  c['roller.cd'] = v.cd;
  for (const f of rollerExtras()) c[f.key] = v[extraName(f.key)];
  return c;
}

// The input that shows an engine message about field `key` (or a message naming it).
function inputForKey(key) {
  if (key === 'MMd') return rollerInput('MMd') ? 'MMd' : 'torque';
  if (extras.some((f) => f.key === key)) return extraName(key);
  if (key === 'trough.a') return $('trough_mode').value === 'spiral' ? 'a' : 'R';
  for (const [name, spec] of Object.entries(INPUTS)) if (spec.key === key && name !== 'R' && name !== 'a') return name;
  return null;
}


// ---------------------------------------------------------------- URL state

// An input's name in the URL: its own, or its field key (roller.static_moment, roller.exciter).
const urlName = (name) => INPUTS[name].param || name;

function saveUrl() {
  const p = new URLSearchParams();
  p.set('roller.type', currentRoller());
  p.set('soil', $('soil_mode').value);
  p.set('trough', $('trough_mode').value);
  if ($('rolling').checked) p.set('rolling', '1');
  if ($('M0_scale').checked) p.set('M0f2', '1');
  for (const name of visibleInputs()) if (!name.startsWith('x:')) p.set(urlName(name), inputText(name));
  // the other fields of the roller only when they differ from its defaults, by their keys
  for (const f of rollerExtras()) if (extraText(f) !== extraDefaultText(f)) p.set(f.key, extraText(f));
  history.replaceState(null, '', `${location.pathname}?${p}`);
}

function loadUrl() {
  const p = new URLSearchParams(location.search);
  // What the link gives that the page cannot take (a misspelled choice, a boolean other than
  // true/false): said above the results, not replaced by a default without a word.
  const problems = [];
  const choice = (f, text) => {
    if (choiceIndex(f, text) < 0) problems.push(`${f.key} = '${text}' is not one of ${f.choices.join(', ')}: ${f.choices[0]} is used`);
  };
  const boolean = (name, text) => {
    if (!['true', 'false', '1', '0'].includes(text)) problems.push(`${name} = '${text}' is not true or false: false is used`);
  };
  if (p.has('roller.type')) choice(fieldByKey['roller.type'], p.get('roller.type'));
  for (const [name, values] of [['soil', ['table2', 'modulus']], ['trough', ['circle', 'spiral']]])
    if (p.has(name) && !values.includes(p.get(name))) problems.push(`${name} = '${p.get(name)}' is not one of ${values.join(', ')}: ${values[0]} is used`);
  for (const name of ['rolling', 'M0f2']) if (p.has(name)) boolean(name, p.get(name));
  // the choice inputs above the extras (the vibratory drum's roller.exciter)
  for (const spec of Object.values(INPUTS)) {
    const f = spec.key && fieldByKey[spec.key];
    if (f && f.type === 'choice' && p.has(spec.param || spec.key)) choice(f, p.get(spec.param || spec.key));
  }
  for (const f of extras) {
    if (!p.has(f.key)) continue;
    if (f.type === 'choice') choice(f, p.get(f.key));
    if (f.type === 'boolean') boolean(f.key, p.get(f.key));
  }
  const known = new Set(['roller.type', 'soil', 'trough', 'rolling', 'M0f2', ...Object.keys(INPUTS).map(urlName), ...extras.map((f) => f.key)]);
  for (const key of p.keys()) if (!known.has(key)) problems.push(`'${key}' is not a parameter of this page: ignored`);
  // The roller first (by its name, or its index as older links wrote it), with its defaults; the
  // URL's inputs then override them.
  const rollerField = fieldByKey['roller.type'];
  const roller = rollerField.choices[Math.max(0, choiceIndex(rollerField, p.get('roller.type') ?? ''))];
  $('roller_type').value = roller;
  applyRoller(roller);
  if (p.get('soil') === 'modulus') $('soil_mode').value = 'modulus';
  if (p.get('trough') === 'spiral') $('trough_mode').value = 'spiral';
  $('rolling').checked = ['1', 'true'].includes(p.get('rolling'));
  $('M0_scale').checked = ['1', 'true'].includes(p.get('M0f2'));
  for (const name of Object.keys(INPUTS)) if (p.has(urlName(name))) setInputText(name, p.get(urlName(name)));
  for (const f of extras) if (p.has(f.key)) setExtra(f, p.get(f.key));
  // A parameter the chosen roller, soil or trough does not read (M0 for the vibratory drum, nu of
  // a Table 2 soil): said, as the command line refuses it, not dropped without a word.
  updateVisibility();
  const shown = new Set(visibleInputs());
  for (const name of Object.keys(INPUTS))
    if (p.has(urlName(name)) && !shown.has(name)) problems.push(`${urlName(name)} = '${p.get(urlName(name))}' has no effect with this roller, soil and trough: ignored`);
  for (const f of extras)
    if (p.has(f.key) && !shown.has(extraName(f.key))) problems.push(`${f.key} = '${p.get(f.key)}' has no effect with this roller: ignored`);
  $('url-note').textContent = problems.length ? `The link: ${problems.join('; ')}.` : '';
  $('url-note').hidden = problems.length === 0;
}

// ---------------------------------------------------------------- the worker

function startWorker() {
  worker = new Worker('worker.js');
  worker.onmessage = (ev) => onMessage(ev.data);
  worker.onerror = (ev) => {
    showStatus(`engine error: ${ev.message}`, false);
    busySince = 0;
  };
}

function request(values, checkOnly = false) {
  seq += 1;
  const msg = { type: 'run', seq, values, n_max: N_MAX, checkOnly };
  if (busySince === 0) {
    send(msg);
  } else if (performance.now() - busySince > 1000) {
    // a long case (e.g. one that never becomes steady) is still running: drop it
    worker.terminate();
    startWorker();
    send(msg);
  } else {
    pending = msg;
  }
}

function send(msg) {
  busySince = performance.now();
  pending = null;
  worker.postMessage(msg);
  if (msg.checkOnly) return;
  // Until the answer comes nothing on screen may pass for the new case's: the status says it is
  // computing, and the previous case's results are faded (a case that takes seconds showed the
  // previous one's green "steady state" and its metrics meanwhile).
  $('results').classList.add('busy');
  showStatus('computing this case … (the results below are still the previous case\'s)', null, '');
  for (const id of STALE_WHILE_BUSY) $(id).classList.add('stale');
}

// What is faded while a case computes.
const STALE_WHILE_BUSY = ['plot-time', 'plot-figure', 'drum', 'metrics', 'plot-spec-x', 'plot-spec-z', 'area-caption', 'timing'];

function onMessage(msg) {
  if (msg.type === 'ready') {
    if (fields.length) return;  // a restarted worker (see request): the page is set up
    fields = msg.fields;
    fieldByKey = Object.fromEntries(fields.map((f) => [f.key, f]));
    soilKeys = msg.soilKeys;
    rollerKeys = msg.rollerKeys;
    $('engine-version').textContent = `Engine: oscidrum ${msg.version} (WebAssembly).`;
    init();
    return;
  }
  if (msg.type !== 'result') return;
  busySince = 0;
  if (pending) {
    send(pending);
  }
  if (msg.seq !== seq) return;  // an answer to an outdated request
  for (const id of STALE_WHILE_BUSY) $(id).classList.remove('stale');
  $('results').classList.remove('busy');
  const { values } = readInputs();
  // Every invalid input at once: the page's own messages (empty, not a number) and the engine's
  // rule of every other field.
  for (const name of visibleInputs()) setError(name, inputErrors[name] || '');
  if (Object.keys(msg.errors).length || !msg.result) {
    for (const [key, message] of Object.entries(msg.errors)) {
      const name = inputForKey(key);
      if (name && !inputErrors[name]) setError(name, inputMessage(name, message));
    }
    showInvalid(invalidText());
    markReady();
    return;
  }
  const r = msg.result;
  if (!r.ok) {
    // the input of the parameter the error is about (the engine's error carries its key)
    const name = r.key ? inputForKey(r.key) : null;
    if (name && visibleInputs().includes(name)) setError(name, inputMessage(name, r.error));
    showInvalid(`invalid input: ${r.error}`);
    markReady();
    return;
  }
  last = { result: r, ms: msg.ms, inputs: values };
  render();
  markReady();
}

// The ready marker (scripts/screenshot-web.sh, the tests): set once the first case is shown.
function markReady() {
  if (document.body.dataset.ready === 'true') return;
  document.body.dataset.ready = 'true';
  document.body.classList.add('ready');
}

// The exports follow what is on screen: the case file only for inputs that are valid (it wrote the
// last valid case while the inputs read otherwise), the plots only of a steady state (the SVG of
// a run without one was an empty file).
function setExports(caseOk, steadyOk) {
  $('export-toml').disabled = !caseOk;
  $('export-toml').title = caseOk ? 'a case file for oscidrum run' : 'the inputs are not valid: no case to export';
  // The samples on screen are an earlier case's while the inputs are invalid.
  $('export-csv').disabled = !caseOk;
  $('export-csv').title = caseOk ? 'the sampled steady state' : 'the inputs are not valid: the samples shown are an earlier case\'s';
  for (const id of ['export-png', 'export-svg']) {
    $(id).disabled = !steadyOk;
    $(id).title = steadyOk ? '' : 'no steady state: no plots to export';
  }
}

// While an input is invalid, what is on screen is an earlier case's: faded, nothing to export,
// and the status says so. (The previous case's table read 'steady_state' at full strength beside
// an invalid form, its CSV still exported; a record's redraw turned the status green and the case
// file on again, exporting the last valid case.)
function showInvalid(text) {
  showStatus(text, false);
  setExports(false, false);
  for (const id of STALE_WHILE_BUSY) $(id).classList.add('stale');
}

function invalidText() {
  const count = document.querySelectorAll('.field.invalid').length;
  return `invalid input (${count} ${count === 1 ? 'field' : 'fields'}): see the messages next to the inputs`;
}

function showStatus(text, ok, value = '') {
  const s = $('status');
  s.textContent = text;
  s.className = ok === null ? 'busy' : ok ? 'ok' : 'bad';
  s.dataset.value = value;
}

function onChange() {
  updateVisibility();
  const { values, errors } = readInputs();
  inputErrors = errors;
  for (const name of [...Object.keys(INPUTS), ...extras.map((f) => extraName(f.key))]) setError(name, errors[name] || '');
  if (Object.keys(errors).length) {
    showInvalid('invalid input: see the messages next to the inputs');
    // The other inputs are checked against their rules all the same (nothing is computed), so
    // that every invalid input is flagged at once, not only the first.
    const parsed = Object.fromEntries(Object.entries(caseValues(values)).filter(([, v]) => Number.isFinite(v)));
    request(parsed, true);
    return;
  }
  saveUrl();
  request(caseValues(values));
}

// ---------------------------------------------------------------- rendering

function render() {
  const { result: r, ms } = last;
  const ok = r.status === 'steady_state';
  const m = r.metrics;
  if (document.querySelectorAll('.field.invalid').length) {
    showInvalid(invalidText());  // redrawn for a record: still the earlier case's
  } else {
    showStatus(ok ? `steady state (${r.message})` : `${r.status}: ${r.message}`, ok, r.status);
    setExports(true, !!m);
  }
  // A field set away from its default that this case does not read (contact.v_eps under
  // Coulomb's law): said, as the command line refuses it (the page computed the default case
  // without a word).
  const idle = rollerExtras().filter((f) => r.in_effect && r.in_effect[f.key] === false && extraText(f) !== extraDefaultText(f));
  $('effect-note').textContent = idle.length
    ? `No effect in this case (the engine does not read ${idle.length === 1 ? 'it' : 'them'}): ${idle.map((f) => `${f.key} = ${extraText(f)}`).join(', ')}.`
    : '';
  $('effect-note').hidden = idle.length === 0;
  $('timing').textContent = `computed in ${ms.toFixed(0)} ms: ${r.diagnostics.periods_simulated} periods, ` +
    `${r.diagnostics.steps} steps, ${r.diagnostics.switches} stick/slip switches`;
  if (!m) {
    // Not a steady state: the last periods are drawn (as the CLI samples them), without metrics.
    $('area-caption').textContent = '—';
    $('area-caption').dataset.value = '';
    // Nothing of an earlier case stays on screen: no figure, no spectra without a steady state.
    clearPlots(['plot-spec-x', 'plot-spec-z'], ['plot-figure'], 'no steady state: no figure, no spectrum');
    if (r.samples && r.samples.t.length > 0) {
      drawTimePlot(r);
      startAnimation(r);
    } else {
      clearPlots(['time'], ['drum'], `no periods sampled: the run stopped with ${r.status}`);
    }
    const body = $('metrics').tBodies[0];
    body.innerHTML = '';
    const tr = body.insertRow();
    for (const text of ['status', r.status, `no metrics: ${r.message}`]) tr.insertCell().textContent = text;
    return;
  }
  const absentColumn = ['ddx_M', 'ddz_M'].find((c) => isAbsent(r, c));
  $('area-caption').textContent = absentColumn
    ? `0 (${SIGNAL_NAME[absentColumn]} absent${m.area !== 0 ? `: round-off ${fmt(m.area, 2)} m²/s⁴` : ''})`
    : `${fmt(m.area, 5)} m²/s⁴`;
  $('area-caption').dataset.value = String(m.area);
  drawTimePlot(r);
  drawFigure($('plot-figure'), r, m);
  const rec = recordState.analysis && recordState.analysis.ok && recordState.analysis.valid ? recordState.analysis.metrics : null;
  const n = periodSlice(r);
  drawSpectrum('plot-spec-x', m.ddx_harmonics.amplitude, COLORS.x, rec && Array.from(rec.ddx_harmonics.amplitude),
    isAbsent(r, 'ddx_M') ? absentNote(r, ['ddx_M'], n) : null);
  drawSpectrum('plot-spec-z', m.ddz_harmonics.amplitude, COLORS.z, rec && Array.from(rec.ddz_harmonics.amplitude),
    isAbsent(r, 'ddz_M') ? absentNote(r, ['ddz_M'], n) : null);
  fillMetrics(r, m);
  startAnimation(r);
}

// Remove the uPlot plots `ids` and blank the canvases `canvasIds` with a note (what is not drawn).
function clearPlots(ids, canvasIds, note) {
  for (const id of ids) {
    if (plots[id]) { plots[id].destroy(); delete plots[id]; }
  }
  if (canvasIds.includes('drum') && animation) cancelAnimationFrame(animation.frame);
  for (const id of canvasIds) {
    const c = $(id), ctx = c.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, c.width, c.height);
    ctx.fillStyle = '#666'; ctx.font = '12px system-ui, sans-serif'; ctx.textAlign = 'center';
    ctx.fillText(note, c.width / 2, c.height / 2);
    c.dataset.measuredPoints = '0';
  }
}

function periodSlice(r) {
  // the first two periods of the sampled steady state: 2 p excitation periods for an orbit of
  // period p T (all of them if fewer; a period-2 orbit showed one of its periods, captioned two)
  const p = Math.max(1, r.diagnostics.multiplicity || 1);
  return Math.min(r.samples.t.length, 2 * p * r.samples_per_period);
}

function phaseRuns(phase, n) {
  // contiguous runs of one phase: [{from, to, phase}]
  const runs = [];
  let start = 0;
  for (let i = 1; i <= n; i++) {
    if (i === n || phase[i] !== phase[start]) {
      runs.push({ from: start, to: i, phase: phase[start] });
      start = i;
    }
  }
  return runs;
}

// 0 stick, 1 slip+, -1 slip-, 2 flight (contact.unilateral)
const phaseColor = (p) => (p === 0 ? COLORS.stick : p === 2 ? COLORS.flight : p > 0 ? COLORS.slipp : COLORS.slipn);
const phaseName = (p) => (p === 0 ? 'stick' : p === 2 ? 'flight' : p > 0 ? 'slip +' : 'slip −');

function drawTimePlot(r) {
  const s = r.samples;
  const n = periodSlice(r);
  const t0 = s.t[0];
  const t = Array.from(s.t.subarray(0, n), (x) => (x - t0) * 1e3);
  const data = [t, Array.from(s.ddx_M.subarray(0, n)), Array.from(s.ddz_M.subarray(0, n))];
  const runs = phaseRuns(s.phase, n);
  const el = $('plot-time');
  const width = Math.max(400, el.clientWidth || 700);
  if (plots.time) plots.time.destroy();
  // An absent signal (round-off) on the other's scale, named so in the legend.
  const scale = (column) => (isAbsent(r, column) ? { range: absentRange(r, column, n) } : {});
  const legendName = (column, name) => (isAbsent(r, column) ? `${name} (absent: round-off only)` : name);
  plots.time = new uPlot({
    width, height: 240,
    // z_M'' (about +-1 m/s^2) on its own axis at the right: on the axis of x_M'' (+-12) it is a
    // flat line.
    scales: { x: { time: false }, ax: scale('ddx_M'), az: scale('ddz_M') },
    axes: [{ label: 't - t0 [ms]' },
      { label: "x_M'' [m/s²]", scale: 'ax', stroke: COLORS.x },
      { label: "z_M'' (down) [m/s²]", scale: 'az', side: 1, stroke: COLORS.z, grid: { show: false } }],
    series: [{ label: 't [ms]' }, { label: legendName('ddx_M', "x_M''"), stroke: COLORS.x, width: 1.5, scale: 'ax' },
      { label: legendName('ddz_M', "z_M'' (down)"), stroke: COLORS.z, width: 1.5, scale: 'az' }],
    hooks: {
      drawClear: [(u) => {
        const ctx = u.ctx;
        ctx.save();
        for (const run of runs) {
          const x0 = u.valToPos(t[run.from], 'x', true);
          const x1 = u.valToPos(t[Math.min(run.to, n - 1)], 'x', true);
          ctx.fillStyle = phaseColor(run.phase);
          ctx.fillRect(x0, u.bbox.top, Math.max(1, x1 - x0), u.bbox.height);
        }
        ctx.restore();
      }],
    },
  }, data, el);
}

// The spectrum A_n [m/s²] as bars; a measured record's as dots over them, on the same scale (the
// identified model and the record side by side, as `oscidrum run --plot` draws them).
// `absent`: the note for a signal that is round-off (no bars: they would be round-off's).
function drawSpectrum(id, amplitudes, color, measured = null, absent = null) {
  const a = absent ? Array.from(amplitudes, () => 0) : Array.from(amplitudes);
  const x = a.map((_, i) => i);
  const series = [{ label: 'n' }, { label: 'A_n [m/s²]', stroke: color, fill: color + '99', paths: uPlot.paths.bars({ size: [0.6, 40] }), points: { show: false } }];
  const data = [x, a];
  let top = Math.max(...a);
  if (measured) {
    data.push(x.map((i) => (i < measured.length ? measured[i] : null)));
    top = Math.max(top, ...measured.slice(0, a.length));
    series.push({ label: 'measured', stroke: COLORS.measured, paths: () => null, points: { show: true, size: 7, fill: COLORS.measured } });
  }
  const el = $(id);
  if (plots[id]) plots[id].destroy();
  plots[id] = new uPlot({
    width: 420, height: 200,
    scales: { x: { time: false, range: [-0.5, a.length - 0.5] }, y: { range: [0, 1.05 * (top || 1)] } },
    axes: [{ label: 'n (harmonic n f)', splits: () => x }, { label: 'A_n [m/s²]', size: 60 }],
    series,
    legend: { show: false },
  }, data, el);
  // The note of an absent signal under the plot (an element of the page, for reading and tests).
  let note = el.querySelector('.absent-note');
  if (!note) {
    note = document.createElement('p');
    note.className = 'absent-note';
    el.appendChild(note);
  }
  note.textContent = absent || '';
  note.hidden = !absent;
}

// ---- plain canvas plots (the z-x figure, the drum)

function niceTicks(lo, hi, count = 5) {
  const span = hi - lo || 1;
  const step0 = span / count;
  const mag = 10 ** Math.floor(Math.log10(step0));
  const step = [1, 2, 5, 10].map((k) => k * mag).find((s) => span / s <= count) || 10 * mag;
  const ticks = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) ticks.push(Math.abs(v) < 1e-12 * span ? 0 : v);
  return ticks;
}

// Axes box for canvas plots: returns mapping functions.
function frame(ctx, w, h, xr, yr, xlabel, ylabel, top = 10) {
  const box = { l: 52, r: w - 10, t: top, b: h - 36 };
  const X = (v) => box.l + ((v - xr[0]) / (xr[1] - xr[0])) * (box.r - box.l);
  const Y = (v) => box.b - ((v - yr[0]) / (yr[1] - yr[0])) * (box.b - box.t);
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, w, h);
  ctx.strokeStyle = '#ddd';
  ctx.fillStyle = '#333';
  ctx.font = '11px system-ui, sans-serif';
  ctx.lineWidth = 1;
  ctx.textAlign = 'center';
  for (const v of niceTicks(xr[0], xr[1])) {
    ctx.beginPath(); ctx.moveTo(X(v), box.t); ctx.lineTo(X(v), box.b); ctx.stroke();
    ctx.fillText(fmt(v, 4), X(v), box.b + 14);
  }
  ctx.textAlign = 'right';
  for (const v of niceTicks(yr[0], yr[1])) {
    ctx.beginPath(); ctx.moveTo(box.l, Y(v)); ctx.lineTo(box.r, Y(v)); ctx.stroke();
    ctx.fillText(fmt(v, 4), box.l - 4, Y(v) + 4);
  }
  ctx.strokeStyle = '#888';
  ctx.strokeRect(box.l, box.t, box.r - box.l, box.b - box.t);
  ctx.textAlign = 'center';
  ctx.fillText(xlabel, (box.l + box.r) / 2, h - 6);
  ctx.save(); ctx.translate(12, (box.t + box.b) / 2); ctx.rotate(-Math.PI / 2); ctx.fillText(ylabel, 0, 0); ctx.restore();
  return { X, Y, box };
}

function range(arr, pad = 0.05) {
  let lo = Infinity, hi = -Infinity;
  for (const v of arr) { if (v < lo) lo = v; if (v > hi) hi = v; }
  const d = (hi - lo) * pad || 1;
  return [lo - d, hi + d];
}

function drawFigure(canvas, r, m) {
  const s = r.samples;
  const n = Math.min(s.t.length, r.samples_per_period * Math.max(1, r.diagnostics.multiplicity));
  const x = s.ddx_M.subarray(0, n), z = s.ddz_M.subarray(0, n);
  // the measured record's figure (one period of its fit), drawn over the model's
  const measured = recordState.analysis && recordState.analysis.ok && recordState.analysis.valid ? recordState.analysis.periodic : null;
  const xs = measured ? [...x, ...measured.ddx_M] : x, zs = measured ? [...z, ...measured.ddz_M] : z;
  const ctx = canvas.getContext('2d');
  // A coordinate that is round-off (and no record over it) spans the other's range: a line on 0.
  const xAbsent = isAbsent(r, 'ddx_M') && !measured, zAbsent = isAbsent(r, 'ddz_M') && !measured;
  const xr = xAbsent ? absentRange(r, 'ddx_M', n) : range(xs), zr = zAbsent ? absentRange(r, 'ddz_M', n) : range(zs);
  // A top margin for the caption: it must not cover the figure-eight.
  const { X, Y } = frame(ctx, canvas.width, canvas.height, xr, zr, "x_M'' [m/s²]", "z_M'' (down) [m/s²]", 34);
  // the figure coloured by the contact phase
  ctx.lineWidth = 1.8;
  let curveTop = Infinity;
  let flight = false;
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    ctx.strokeStyle = s.phase[i] === 0 ? ARROW.stick : s.phase[i] === 2 ? ARROW.flight : ARROW.slip;
    if (s.phase[i] === 2) flight = true;
    ctx.beginPath(); ctx.moveTo(X(x[i]), Y(z[i])); ctx.lineTo(X(x[j]), Y(z[j])); ctx.stroke();
    curveTop = Math.min(curveTop, Y(z[i]));
  }
  canvas.dataset.measuredPoints = '0';
  if (measured) {
    ctx.strokeStyle = COLORS.measured; ctx.lineWidth = 1.5; ctx.setLineDash([5, 3]);
    const k = measured.ddx_M.length;
    ctx.beginPath();
    for (let i = 0; i <= k; i++) {
      const px = X(measured.ddx_M[i % k]), py = Y(measured.ddz_M[i % k]);
      if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
      curveTop = Math.min(curveTop, py);
    }
    ctx.stroke(); ctx.setLineDash([]);
    canvas.dataset.measuredPoints = String(k);
  }
  ctx.textAlign = 'left';
  const absentColumns = [...(xAbsent ? ['ddx_M'] : []), ...(zAbsent ? ['ddz_M'] : [])];
  if (absentColumns.length) {
    ctx.fillStyle = '#444';
    ctx.font = '10px system-ui, sans-serif';
    // On two lines where one would run past the canvas's right edge (both signals named).
    const note = absentNote(r, absentColumns, n), cut = note.indexOf(' (');
    const lines = ctx.measureText(note).width <= canvas.width - 56 - 8 || cut < 0
      ? [note] : [note.slice(0, cut), note.slice(cut + 1)];
    lines.forEach((line, i) => ctx.fillText(line, 56, canvas.height - 42 - 12 * (lines.length - 1 - i)));
    ctx.font = '11px system-ui, sans-serif';
  }
  const caption = !absentColumns.length ? `area ${fmt(m.area, 5)} m²/s⁴ (both lobes)`
    : m.area !== 0 ? `area 0 (round-off ${fmt(m.area, 2)} m²/s⁴)` : 'area 0';
  ctx.fillStyle = '#222';
  ctx.fillText(caption, 60, 20);
  const after = 60 + ctx.measureText(caption).width + 10;
  ctx.fillStyle = ARROW.stick;
  ctx.fillText('stick', after, 20);
  ctx.fillStyle = ARROW.slip;
  ctx.fillText('slip', after + 34, 20);
  let next = after + 62;
  if (flight) {
    ctx.fillStyle = ARROW.flight;
    ctx.fillText('flight', next, 20);
    next += 38;
  }
  if (measured) {
    ctx.fillStyle = COLORS.measured;
    ctx.fillText('measured', next, 20);
  }
  // where the caption ends and the figure begins [px], for the tests: the caption is above it
  const metrics = ctx.measureText(caption);
  canvas.dataset.captionBottom = String(20 + (metrics.actualBoundingBoxDescent || 3));
  canvas.dataset.curveTop = String(curveTop);
}

// ---- the drum in its trough (animated from the sampled steady state)

let animation = null;

function startAnimation(r) {
  if (animation) cancelAnimationFrame(animation.frame);
  const s = r.samples;
  const n = Math.min(s.t.length, r.samples_per_period * Math.max(1, r.diagnostics.multiplicity));
  let maxN = 0;
  for (let i = 0; i < n; i++) maxN = Math.max(maxN, Math.abs(s.N[i]), Math.abs(s.T[i]));
  const c = r.case;
  animation = { s, n, maxN, r: c['roller.r'], outline: r.trough.outline, frame: 0, start: performance.now() };
  const tick = (now) => {
    // one excitation period takes 2 s on screen
    const i = Math.floor((Math.max(0, now - animation.start) / 2000) * r.samples_per_period) % n;
    drawDrum($('drum'), animation, i);
    animation.frame = requestAnimationFrame(tick);
  };
  drawDrum($('drum'), animation, 0);
  animation.frame = requestAnimationFrame(tick);
}

function arrow(ctx, x0, y0, dx, dy, color) {
  const len = Math.hypot(dx, dy);
  if (len < 1) return;
  ctx.strokeStyle = color; ctx.fillStyle = color; ctx.lineWidth = 3;
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x0 + dx, y0 + dy); ctx.stroke();
  const ux = dx / len, uy = dy / len;
  ctx.beginPath();
  ctx.moveTo(x0 + dx, y0 + dy);
  ctx.lineTo(x0 + dx - 10 * ux + 5 * uy, y0 + dy - 10 * uy - 5 * ux);
  ctx.lineTo(x0 + dx - 10 * ux - 5 * uy, y0 + dy - 10 * uy + 5 * ux);
  ctx.fill();
}

function drawDrum(canvas, an, i) {
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  const { s } = an;
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
  const scale = (0.36 * h) / an.r;  // px per m
  // The drum centre at rest is the origin; the trough moves with the soil point A (x_A, s_A down),
  // exaggerated; the drum centre rolls along the trough by (x_M - x_A, z_M - s_A) = the roll curve
  // (15)-(16), drawn to scale.
  const ox = w / 2 + DISPLACEMENT_FACTOR * s.x_A[i] * scale;
  const oy = 0.47 * h + DISPLACEMENT_FACTOR * s.s_A[i] * scale;
  const d = s.delta[i];
  const mx = ox + (s.x_M[i] - s.x_A[i]) * scale;
  const my = oy + (s.z_M[i] - s.s_A[i]) * scale;
  ctx.fillStyle = '#c8ccd2'; ctx.strokeStyle = '#444'; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.arc(mx, my, an.r * scale, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
  // spokes show the rotation phi (exaggerated)
  const phi = ROTATION_FACTOR * s.phi[i];
  ctx.strokeStyle = '#555'; ctx.lineWidth = 2;
  for (let k = 0; k < 4; k++) {
    const ang = phi + (k * Math.PI) / 2;
    ctx.beginPath(); ctx.moveTo(mx, my);
    ctx.lineTo(mx + 0.85 * an.r * scale * Math.sin(ang), my - 0.85 * an.r * scale * Math.cos(ang));
    ctx.stroke();
  }
  ctx.fillStyle = '#b00'; ctx.beginPath();
  ctx.arc(mx + 0.85 * an.r * scale * Math.sin(phi), my - 0.85 * an.r * scale * Math.cos(phi), 5, 0, 2 * Math.PI); ctx.fill();
  // soil and trough, drawn over the drum: the drum shows only inside the trough. The trough's
  // surface comes from the engine (the shape's own kinematics), then the flat soil surface.
  ctx.fillStyle = '#d9c9a8';
  const { x: tx0, z: tz0 } = an.outline;
  const yEdge = oy + tz0[0] * scale;
  ctx.beginPath();
  ctx.moveTo(0, h);
  ctx.lineTo(0, yEdge);
  for (let j = 0; j < tx0.length; j++) ctx.lineTo(ox + tx0[j] * scale, oy + tz0[j] * scale);
  ctx.lineTo(w, oy + tz0[tz0.length - 1] * scale);
  ctx.lineTo(w, h);
  ctx.closePath();
  ctx.fill();
  ctx.strokeStyle = '#8a6d3b'; ctx.lineWidth = 2; ctx.stroke();
  // contact point P and the forces on the drum: N along the normal (towards M), T along the tangent
  const px = mx + an.r * Math.sin(d) * scale, py = my + an.r * Math.cos(d) * scale;
  const len = (0.32 * h) / (an.maxN || 1);
  const stick = s.phase[i] === 0;
  const color = stick ? ARROW.stick : ARROW.slip;
  const nx = -Math.sin(d), ny = -Math.cos(d);  // unit normal towards the drum centre (screen)
  const tx = Math.cos(d), ty = -Math.sin(d);   // unit tangent (x to the right at the bottom)
  arrow(ctx, px, py, nx * s.N[i] * len, ny * s.N[i] * len, color);
  arrow(ctx, px, py, tx * s.T[i] * len, ty * s.T[i] * len, color);
  ctx.fillStyle = '#222'; ctx.font = '12px system-ui, sans-serif'; ctx.textAlign = 'left';
  ctx.fillText(`t - t0 = ${((s.t[i] - s.t[0]) * 1e3).toFixed(2)} ms   ${phaseName(s.phase[i])}`, 8, 16);
  ctx.fillText(`N = ${(s.N[i] / 1e3).toFixed(1)} kN   T = ${(s.T[i] / 1e3).toFixed(1)} kN   δ = ${s.delta[i].toFixed(4)} rad`, 8, 32);
}

// ---- metrics panel

// The three largest harmonics n >= 1 of a spectrum, by amplitude, as "A_n = value" (a fixed set of
// n hides the dominant ones: z's A1 with a driving torque, x's A2).
function largestHarmonics(a) {
  const n = [];
  for (let k = 1; k < a.length; k++) n.push(k);
  n.sort((i, j) => a[j] - a[i]);
  return n.slice(0, 3).sort((i, j) => i - j).map((k) => `A${k} = ${fmt(a[k], 4)}`).join(', ');
}

// A signal that is round-off as a whole (r.absent, the engine's oscidrum::absent_signals: every
// harmonic below 1e-6 of the two signals' largest or 1e-12 g; the vertical exciter's x_M'', both
// signals of a drum without friction) is drawn flat on zero on the other signal's scale and named
// absent, not scaled up to look like a signal.
const SIGNAL_NAME = { ddx_M: "x_M''", ddz_M: "z_M''" };
const isAbsent = (r, column) => Boolean(r && r.absent && r.absent[column]);
function peakOf(values, n = values.length) {
  let top = 0;
  for (let i = 0; i < n; i++) top = Math.max(top, Math.abs(values[i]));
  return top;
}
// The symmetric range [-1.05 top, 1.05 top] of the other signal, for an absent one; [-1, 1] m/s²
// where both are absent (a drum without friction).
function absentRange(r, column, n) {
  const other = column === 'ddx_M' ? 'ddz_M' : 'ddx_M';
  const top = isAbsent(r, other) ? 0 : peakOf(r.samples[other], n);
  return top > 0 ? [-1.05 * top, 1.05 * top] : [-1, 1];
}
// The note for the absent signals `columns` (one or both), with the size of their round-off.
function absentNote(r, columns, n) {
  const names = columns.map((c) => SIGNAL_NAME[c]);
  const bounds = columns.map((c) => `|${SIGNAL_NAME[c]}| ≤ ${fmt(peakOf(r.samples[c], n), 2)}`).join(', ');
  return `${names.join(' and ')} absent: round-off only (${bounds} m/s²)`;
}

// The name of a choice field's value in the case of a result ('vibratory').
const choiceOf = (r, key) => fieldByKey[key].choices[r.case[key]];

function fillMetrics(r, m) {
  const hx = m.ddx_harmonics.amplitude, hz = m.ddz_harmonics.amplitude;
  const num = (v, digits = 4) => (Number.isFinite(v) ? fmt(v, digits) : 'n/a');
  // The rows of each roller: the oscillation drum's phase lags of phi (the torque's response) and
  // of z_M'' at 2f; the vibratory drum's indicators (kb, the CMV- and RMV-type values) and its
  // operating mode; the contact's opening where it may open.
  const vibratory = choiceOf(r, 'roller.type') === 'vibratory';
  const unilateral = r.case['contact.unilateral'] === 1;
  const ksv = fieldByKey['soil.ksv'];
  const rows = [
    ['status', r.status, 'steady period ' + r.diagnostics.multiplicity + ' × 1/f, found after ' + r.diagnostics.periods_to_steady + ' periods'],
  ];
  if (vibratory) rows.push(['operating mode', r.diagnostics.operating_mode, 'the literature\'s names (docs/model.md section 14)']);
  else if (unilateral) rows.push(['contact mode', r.diagnostics.contact_mode, '']);
  // A signal that is round-off: said so, its round-off's size beside it.
  const absentText = (column, text) => (isAbsent(r, column) ? `absent: round-off only (${text})` : text);
  const areaText = isAbsent(r, 'ddx_M') || isAbsent(r, 'ddz_M') ? (m.area !== 0 ? `0 (round-off ${fmt(m.area, 2)})` : '0') : fmt(m.area, 6);
  rows.push(
    ["x_M'' max / min", absentText('ddx_M', `${fmt(m.ddx_max, 5)} / ${fmt(m.ddx_min, 5)}`), 'm/s²'],
    ["z_M'' max / min", absentText('ddz_M', `${fmt(m.ddz_max, 5)} / ${fmt(m.ddz_min, 5)}`), 'm/s², z down'],
    ["x_M'' largest harmonics", isAbsent(r, 'ddx_M') ? 'absent: round-off only' : largestHarmonics(hx), 'm/s² (A_n of n f)'],
    ["z_M'' largest harmonics", isAbsent(r, 'ddz_M') ? 'absent: round-off only' : largestHarmonics(hz), 'm/s²'],
  );
  if (vibratory) {
    rows.push(
      ['kb', num(m.kb / ksv.display_scale, 5), `${ksv.display_unit}: the soil's vertical force in phase with z_M at f, over z_M's amplitude (Kb-type stiffness)`],
      ['CMV-type, RMV-type', [m.cmv, m.rmv].map((v) => num(v)).join(', '), '300 A2/A1 and A(f/2)/A(f) of z_M\'\''],
      ['x THD', num(m.ddx_thd), 'overtones of x_M\'\''],
      ['area', areaText, 'm²/s⁴'],
    );
  } else {
    rows.push(
      ['CMV-type, x THD', [m.cmv, m.ddx_thd].map((v) => num(v)).join(', '), '300 A2/A1 of z_M\'\' (n/a: its A1 is 0); overtones of x_M\'\''],
      ['lag of φ behind the torque', num(m.phi_lag, 5), 'π rad (Fig. 10; n/a: no oscillating torque, M0 = 0)'],
      ["lag x_M''→z_M'' ψ", num(m.psi_xz, 5), 'rad (θ2(z) − 2 θ1(x); n/a: x_M\'\' has no fundamental or z_M\'\' no 2f)'],
      ['area', areaText, 'm²/s⁴ (Figs. 16, 22)'],
    );
  }
  const shares = [m.stick_fraction, m.slip_positive_fraction, m.slip_negative_fraction, ...(unilateral ? [m.flight_fraction] : [])];
  rows.push([`stick / slip+ / slip−${unilateral ? ' / flight' : ''}`, shares.map((v) => fmt(100 * v, 3) + ' %').join(' / '), 'of the time']);
  if (unilateral) {
    rows.push(['lift-offs, largest gap', `${fmt(m.liftoffs_per_period, 3)}, ${fmt(m.gap_max * 1e3, 4)}`, 'per period, mm']);
  }
  // With lift-off N falls to 0 at every lift-off, where max |T| / N has no bound (its value
  // depends on where the samples or steps fall): not a friction any rolling needs.
  const liftoff = m.flight_fraction > 0;
  rows.push(
    ['required μ', liftoff ? 'n/a' : fmt(m.mu_required, 4), liftoff ? 'the drum lifts off: N reaches 0, where |T| / N has no bound' : 'max |T| / N (pure rolling needs this friction)'],
    ['δ max / min', `${fmt(m.delta_max, 4)} / ${fmt(m.delta_min, 4)}`, 'rad'],
  );
  // The soil the model uses (its one conversion of the soil input), in the fields' display units.
  const soil = r.soil;
  const shown = (key) => `${fmt(soil[key.slice(5)] / fieldByKey[key].display_scale, 4)}`;
  const unit = (key) => fieldByKey[key].display_unit;
  rows.push(['soil', `${soil.summary}:${soil.a0 ? ` a0 ${fmt(soil.a0, 4)} m;` : ''} ksh ${shown('soil.ksh')}, ksv ${shown('soil.ksv')} ${unit('soil.ksv')}; ` +
    `csh ${shown('soil.csh')}, csv ${shown('soil.csv')} ${unit('soil.csv')}`, '']);
  rows.push(['trough', r.trough.summary, '']);
  if (vibratory) {
    // F0 = m_u e_u nu^2 (docs/model.md section 14)
    const F0 = r.case['roller.static_moment'] * (2 * Math.PI * r.case['roller.f']) ** 2;
    rows.push(['m_u e_u, F0, exciter', `${fmt(r.case['roller.static_moment'], 6)} kg m, ${fmt(F0 / 1e3, 5)} kN, ${choiceOf(r, 'roller.exciter')}`, 'F0 = m_u e_u ν²']);
    rows.push(['MMd', fmt(r.case.MMd, 6), 'N m']);
  } else {
    // the moment the engine used: from the unbalance (5) when one is given
    const u = r.case['roller.unbalance'];
    const M0 = u > 0 ? oscillationMoment(u, r.case['roller.f']) : r.case['roller.M0'];
    rows.push(['M0, MMd', `${fmt(M0, 6)}, ${fmt(r.case.MMd, 6)}`, u > 0 ? 'N m (M0 = 4 m_u e_u e_w ν² of the unbalance)' : 'N m']);
  }
  const body = $('metrics').tBodies[0];
  body.innerHTML = '';
  for (const [name, value, unit] of rows) {
    const tr = body.insertRow();
    const th = document.createElement('th');
    th.textContent = name;
    tr.appendChild(th);
    tr.insertCell().textContent = value;
    const u = tr.insertCell();
    u.textContent = unit;
    u.style.textAlign = 'left';
    tr.dataset.metric = name;
  }
}

// ---------------------------------------------------------------- a measured record

// A CSV record dropped onto the page (or picked): read, analysed and identified by the engine in
// a second worker (seconds for the identification; the case's worker stays free). The text never
// leaves the browser.
const recordState = { file: null, seq: 0, analysis: null, identification: null, worker: null, ms: {} };

function recordOptions() {
  return { units: $('record-units').value, x_positive: $('record-x').value, z_positive: $('record-z').value };
}

function startRecordWorker() {
  recordState.worker = new Worker('worker.js');
  recordState.worker.onmessage = (ev) => onRecordMessage(ev.data);
  recordState.worker.onerror = (ev) => {
    recordState.busy = false;
    showRecordStatus(`engine error: ${ev.message}`, false);
  };
}

// Read and identify the record with the current options and the current case (its roller, and
// G on the scale of the soil input: Table 2 or Appendix B).
function analyseRecord() {
  const file = recordState.file;
  if (!file) return;
  const { values, errors } = readInputs();
  if (Object.keys(errors).length) {
    showRecordStatus('fix the case inputs first: the record is compared with that case', false);
    return;
  }
  if (recordState.busy) {
    // an identification is running: abandon it
    recordState.worker.terminate();
    startRecordWorker();
  }
  // the record's engine loads with the first record, not with the page (which it would slow)
  if (!recordState.worker) startRecordWorker();
  recordState.seq += 1;
  recordState.analysis = null;
  recordState.identification = null;
  recordState.busy = true;
  const soilScale = $('soil_mode').value === 'modulus' ? 'formulas' : 'table2';
  showRecordStatus(`reading ${file.name} ...`, true);
  recordState.worker.postMessage({ type: 'record', seq: recordState.seq, text: file.text, name: file.name,
    options: recordOptions(), values: caseValues(values), soilScale });
  $('record-clear').disabled = false;
  $('record-again').disabled = false;
  fillRecordTable();
}

function onRecordMessage(msg) {
  if (msg.type === 'ready' || msg.seq !== recordState.seq) return;
  if (msg.type === 'record-analysis') {
    recordState.analysis = msg.analysis;
    recordState.ms.analysis = msg.ms;
    const a = msg.analysis;
    if (!a.ok) {
      recordState.busy = false;
      showRecordStatus(`cannot read the record: ${a.error}`, false);
    } else if (!a.valid) {
      showRecordStatus(`record read, but its fit fails a quality gate: ${a.reason}; identifying the soil ...`, false);
    } else {
      showRecordStatus(`record analysed in ${msg.ms.toFixed(0)} ms; identifying the soil ...`, true);
    }
    if (last) render();
  } else if (msg.type === 'record-identification') {
    recordState.busy = false;
    recordState.identification = msg.identification;
    recordState.ms.identification = msg.ms;
    const id = msg.identification;
    if (!id.ok) showRecordStatus(`identification failed: ${id.error}`, false);
    else if (!id.valid) showRecordStatus(`no identification: ${id.reason}`, false);
    else showRecordStatus(`soil identified in ${(msg.ms / 1000).toFixed(1)} s (${id.simulations} simulations)`, id.warnings.length === 0, 'identified');
  }
  fillRecordTable();
}

function showRecordStatus(text, ok, value = '') {
  const el = $('record-status');
  el.textContent = text;
  el.className = ok ? 'ok' : 'bad';
  el.dataset.value = value;
}

// An estimate as value +- u [lower, upper] in the field's display unit (MN/m^2 for G).
function estimateText(e) {
  const field = e.name === 'G' ? fieldByKey['soil.G'] : null;
  const scale = field ? field.display_scale : 1;
  const unit = prettyUnit(field ? field.display_unit : e.unit);
  const v = (x) => (Number.isFinite(x) ? fmt(x / scale, 4) : '?');
  const lo = `${e.lower_open ? '≤ ' : ''}${v(e.lower)}`, hi = `${e.upper_open ? '≥ ' : ''}${v(e.upper)}`;
  return [`${e.name} = ${v(e.value)} ± ${v(e.u)} ${unit}`, `95 % interval [${lo}, ${hi}] ${unit}`];
}

function fillRecordTable() {
  const body = $('record-table').tBodies[0];
  body.innerHTML = '';
  const row = (name, value, unit = '') => {
    const tr = body.insertRow();
    const th = document.createElement('th');
    th.textContent = name;
    tr.appendChild(th);
    tr.insertCell().textContent = value;
    const u = tr.insertCell();
    u.textContent = unit;
    u.style.textAlign = 'left';
    tr.dataset.record = name;
  };
  const file = recordState.file;
  if (!file) return;
  const a = recordState.analysis;
  row('file', file.name, `${file.text.length} bytes, read in this browser only`);
  if (!a || !a.ok) return;
  const rd = a.reading;
  row('columns', `t: ${rd.t_column}, x_M'': ${rd.x_column}, z_M'': ${rd.z_column}`, `${rd.delimiter}; ${rd.samples} samples over ${fmt(rd.duration, 4)} s`);
  for (const note of rd.notes) row('read as', note);
  row('f', fmt(a.f, 7), 'Hz (estimated from the record)');
  if (!a.valid) {
    row('quality gates', a.reason);
    return;
  }
  const m = a.metrics;
  row('fit residual x, z', `${fmt(m.residual_x, 3)}, ${fmt(m.residual_z, 3)}`, 'RMS of record − fit / RMS');
  row("x_M'' largest harmonics", largestHarmonics(m.ddx_harmonics.amplitude), 'm/s²');
  row("z_M'' largest harmonics", largestHarmonics(m.ddz_harmonics.amplitude), 'm/s²');
  row('area', fmt(m.area, 5), 'm²/s⁴');
  const id = recordState.identification;
  if (!id || !id.ok || !id.valid) return;
  for (const e of id.estimates) {
    const [value, interval] = estimateText(e);
    row(`identified ${e.name}`, value, interval);
  }
  row('scale of G', id.soil_scale === 'table2' ? 'Table 2 (interpolated between its rows)' : 'Appendix B (42)-(45) with the case\'s ν, ρ');
  row('relative residual, reduced χ²', `${fmt(id.relative_residual, 3)}, ${fmt(id.reduced_chi2, 3)}`, 'harmonics n = 1 ... 4');
  // A record sampled in step with the excitation: its raw samples alias (docs/identify.md).
  if (id.model_sampled) row('model compared', 'sampled at the record\'s times', 'the record is sampled in step with the excitation');
  for (const w of id.warnings) row('WARNING', w);
}

function setRecordFile(file) {
  if (!file) return;
  file.text().then((text) => {
    recordState.file = { name: file.name, text };
    analyseRecord();
  });
}

function clearRecord() {
  if (recordState.busy) { recordState.worker.terminate(); startRecordWorker(); recordState.busy = false; }
  recordState.seq += 1;
  recordState.file = null;
  recordState.analysis = null;
  recordState.identification = null;
  $('record-file').value = '';
  $('record-clear').disabled = true;
  $('record-again').disabled = true;
  showRecordStatus('no record', true);
  fillRecordTable();
  if (last) render();
}

function initRecord() {
  // A file dropped anywhere on the page is taken as a record (not opened by the browser).
  document.addEventListener('dragover', (ev) => { ev.preventDefault(); document.body.classList.add('dragging'); });
  document.addEventListener('dragleave', (ev) => { if (!ev.relatedTarget) document.body.classList.remove('dragging'); });
  document.addEventListener('drop', (ev) => {
    ev.preventDefault();
    document.body.classList.remove('dragging');
    const file = ev.dataTransfer && ev.dataTransfer.files[0];
    if (file) setRecordFile(file);
  });
  $('record-file').addEventListener('change', (ev) => setRecordFile(ev.target.files[0]));
  for (const id of ['record-units', 'record-x', 'record-z']) $(id).addEventListener('change', analyseRecord);
  $('record-again').addEventListener('click', analyseRecord);
  $('record-clear').addEventListener('click', clearRecord);
}

// ---------------------------------------------------------------- exports

function download(name, blob) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

function tomlNumber(field, v) {
  if (field.type === 'integer') return String(Math.round(v));
  if (field.type === 'boolean') return v ? 'true' : 'false';
  if (field.type === 'choice') return `"${field.choices[v]}"`;
  const text = String(v);  // the shortest text that reads back exactly
  return /[.eEn]/.test(text) ? text : `${text}.0`;
}

// The case as a TOML file for `oscidrum run` (the keys of the field table in effect).
function caseToml() {
  if (!last) return '';
  const c = last.result.case;
  const lines = ['# oscidrum case exported by the explorer; run it with: oscidrum run case.toml', ''];
  const sections = {};
  // only the keys that take effect (the engine's key_in_effect; oscidrum run refuses the others)
  for (const f of fields) {
    if (!last.result.in_effect[f.key]) continue;
    const dot = f.key.indexOf('.');
    if (dot < 0) lines.push(`${f.key} = ${tomlNumber(f, c[f.key])}  # [${f.unit}] ${f.description}`);
    else (sections[f.key.slice(0, dot)] ||= []).push(`${f.key.slice(dot + 1)} = ${tomlNumber(f, c[f.key])}  # [${f.unit}]`);
  }
  if (sections.soil) sections.soil.unshift(`# ${last.result.soil.summary}`);
  for (const [name, body] of Object.entries(sections)) lines.push('', `[${name}]`, ...body);
  return lines.join('\n') + '\n';
}

// The sampled steady state with the columns of `oscidrum run --csv` (the engine's output table).
function steadyCsv() {
  if (!last) return '';
  const s = last.result.samples;
  const columns = s.columns;
  const out = [columns.map(([n, u]) => `${n}[${u}]`).join(',')];
  for (let i = 0; i < s.t.length; i++) out.push(columns.map(([n]) => String(s[n][i])).join(','));
  return out.join('\n') + '\n';
}

function plotCanvases() {
  return [plots.time && plots.time.ctx.canvas, $('plot-figure'), $('drum'),
    plots['plot-spec-x'] && plots['plot-spec-x'].ctx.canvas, plots['plot-spec-z'] && plots['plot-spec-z'].ctx.canvas].filter(Boolean);
}

function exportPng() {
  const cs = plotCanvases();
  const ratio = window.devicePixelRatio || 1;
  const width = Math.max(...cs.map((c) => c.width));
  const out = document.createElement('canvas');
  out.width = width;
  out.height = cs.reduce((h, c) => h + c.height + 8 * ratio, 0);
  const ctx = out.getContext('2d');
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, out.width, out.height);
  let y = 0;
  for (const c of cs) { ctx.drawImage(c, 0, y); y += c.height + 8 * ratio; }
  out.toBlob((b) => download('oscidrum-plots.png', b), 'image/png');
}

// Vector versions of the plots, drawn from the data.
function svgPlot(x0, y0, w, h, title, xlabel, ylabel, series, shading) {
  const box = { l: x0 + 56, r: x0 + w - 10, t: y0 + 22, b: y0 + h - 36 };
  const xs = series.flatMap((s) => Array.from(s.x)), ys = series.flatMap((s) => Array.from(s.y));
  const xr = series.xr || range(xs, 0), yr = series.yr || range(ys);
  const X = (v) => box.l + ((v - xr[0]) / (xr[1] - xr[0])) * (box.r - box.l);
  const Y = (v) => box.b - ((v - yr[0]) / (yr[1] - yr[0])) * (box.b - box.t);
  const parts = [`<text x="${x0 + 4}" y="${y0 + 14}" font-size="13">${title}</text>`];
  for (const sh of shading || []) parts.push(`<rect x="${X(sh.x0)}" y="${box.t}" width="${Math.max(0.5, X(sh.x1) - X(sh.x0))}" height="${box.b - box.t}" fill="${sh.color}"/>`);
  for (const v of niceTicks(xr[0], xr[1])) parts.push(`<line x1="${X(v)}" x2="${X(v)}" y1="${box.t}" y2="${box.b}" stroke="#ddd"/><text x="${X(v)}" y="${box.b + 14}" font-size="11" text-anchor="middle">${fmt(v, 4)}</text>`);
  for (const v of niceTicks(yr[0], yr[1])) parts.push(`<line x1="${box.l}" x2="${box.r}" y1="${Y(v)}" y2="${Y(v)}" stroke="#ddd"/><text x="${box.l - 4}" y="${Y(v) + 4}" font-size="11" text-anchor="end">${fmt(v, 4)}</text>`);
  parts.push(`<rect x="${box.l}" y="${box.t}" width="${box.r - box.l}" height="${box.b - box.t}" fill="none" stroke="#888"/>`);
  parts.push(`<text x="${(box.l + box.r) / 2}" y="${y0 + h - 6}" font-size="11" text-anchor="middle">${xlabel}</text>`);
  parts.push(`<text transform="translate(${x0 + 12},${(box.t + box.b) / 2}) rotate(-90)" font-size="11" text-anchor="middle">${ylabel}</text>`);
  for (const s of series) {
    if (s.bars) {
      for (let i = 0; i < s.x.length; i++) parts.push(`<rect x="${X(s.x[i]) - 6}" y="${Y(s.y[i])}" width="12" height="${Y(yr[0] < 0 ? 0 : yr[0]) - Y(s.y[i])}" fill="${s.color}"/>`);
    } else {
      const pts = Array.from(s.x, (v, i) => `${X(v).toFixed(2)},${Y(s.y[i]).toFixed(2)}`).join(' ');
      parts.push(`<polyline points="${pts}" fill="none" stroke="${s.color}" stroke-width="1.5"/>`);
    }
  }
  return parts.join('\n');
}

function plotsSvg() {
  if (!last || !last.result.metrics) return '';
  const r = last.result, s = r.samples, m = r.metrics;
  const n = periodSlice(r);
  const t = Array.from(s.t.subarray(0, n), (v) => (v - s.t[0]) * 1e3);
  const shading = phaseRuns(s.phase, n).map((run) => ({ x0: t[run.from], x1: t[Math.min(run.to, n - 1)], color: phaseColor(run.phase) }));
  const np = Math.min(s.t.length, r.samples_per_period * Math.max(1, r.diagnostics.multiplicity));
  const closed = (a) => [...a.subarray(0, np), a[0]];
  // A signal that is round-off: no bars, the figure on the other signal's scale, said so.
  const spec = (h, color, column) => {
    const a = Array.from(h.amplitude, (v) => (isAbsent(r, column) ? 0 : v));
    const out = [{ x: a.map((_, i) => i), y: a, color, bars: true }];
    if (isAbsent(r, column)) out.yr = [0, 1];
    return out;
  };
  const absentTitle = (column) => (isAbsent(r, column) ? ' (absent: round-off only)' : '');
  const figure = [{ x: closed(s.ddx_M), y: closed(s.ddz_M), color: '#333' }];
  if (isAbsent(r, 'ddx_M')) figure.xr = absentRange(r, 'ddx_M', np);
  if (isAbsent(r, 'ddz_M')) figure.yr = absentRange(r, 'ddz_M', np);
  const areaTitle = isAbsent(r, 'ddx_M') || isAbsent(r, 'ddz_M') ? (m.area !== 0 ? `area 0 (round-off ${fmt(m.area, 2)} m²/s⁴)` : 'area 0') : `area ${fmt(m.area, 5)} m²/s⁴`;
  const body = [
    svgPlot(0, 0, 900, 280, `x_M'' (blue), z_M'' (red, down) over two steady periods; shading: stick (green), slip+ (orange), slip- (red)${r.case['contact.unilateral'] === 1 ? ', flight (violet)' : ''}`, 't - t0 [ms]', 'm/s²',
      [{ x: t, y: s.ddx_M.subarray(0, n), color: COLORS.x }, { x: t, y: s.ddz_M.subarray(0, n), color: COLORS.z }], shading),
    svgPlot(0, 290, 440, 320, `z_M'' over x_M'', ${areaTitle}`, "x_M'' [m/s²]", "z_M'' [m/s²]", figure),
    svgPlot(460, 290, 440, 155, `spectrum of x_M''${absentTitle('ddx_M')}`, 'n', 'A_n [m/s²]', spec(m.ddx_harmonics, COLORS.x, 'ddx_M')),
    svgPlot(460, 455, 440, 155, `spectrum of z_M''${absentTitle('ddz_M')}`, 'n', 'A_n [m/s²]', spec(m.ddz_harmonics, COLORS.z, 'ddz_M')),
  ];
  return `<svg xmlns="http://www.w3.org/2000/svg" width="900" height="620" font-family="sans-serif">\n<rect width="900" height="620" fill="#fff"/>\n${body.join('\n')}\n</svg>\n`;
}

// ---------------------------------------------------------------- start

function init() {
  buildInputs();
  loadUrl();
  $('rot-factor').textContent = String(ROTATION_FACTOR);
  $('disp-factor').textContent = String(DISPLACEMENT_FACTOR);
  // A roller chosen starts from its defaults (before the form's listeners read the inputs).
  for (const type of ['input', 'change']) $('roller_type').addEventListener(type, () => applyRoller(currentRoller()));
  $('case-form').addEventListener('input', onChange);
  // the note on the link's parameters holds until the inputs are changed (the URL is then the page's)
  $('case-form').addEventListener('input', () => { $('url-note').hidden = true; });
  $('case-form').addEventListener('change', onChange);
  $('reset').addEventListener('click', () => {
    $('roller_type').value = fieldByKey['roller.type'].choices[fieldByKey['roller.type'].default];
    $('soil_mode').value = 'table2'; $('trough_mode').value = 'circle';
    $('rolling').checked = false; $('M0_scale').checked = false;
    appliedRoller = null;
    applyRoller(currentRoller());
    for (const name of Object.keys(INPUTS)) setInputText(name, defaultText(name));
    for (const f of extras) setExtra(f, extraDefault(f));
    onChange();
  });
  $('export-toml').addEventListener('click', () => download('case.toml', new Blob([caseToml()], { type: 'application/toml' })));
  $('export-csv').addEventListener('click', () => download('steady_state.csv', new Blob([steadyCsv()], { type: 'text/csv' })));
  $('export-png').addEventListener('click', exportPng);
  $('export-svg').addEventListener('click', () => download('oscidrum-plots.svg', new Blob([plotsSvg()], { type: 'image/svg+xml' })));
  $('copy-link').addEventListener('click', () => navigator.clipboard && navigator.clipboard.writeText(location.href));
  $('soil-note').textContent = 'Table 2: the paper\'s coefficients at G = 5, 10, ..., 70 MN/m² (ν = 0.3, ρ = 1900 kg/m³). Modulus: the coefficients from G, ν, ρ by Appendix B (42)-(45).';
  initRecord();
  onChange();
}

// For tests and the console: the current case and exports.
window.explorer = {
  caseToml, steadyCsv, plotsSvg, last: () => last, busy: () => busySince !== 0 || pending !== null,
  // the engine's field table (keys, types, choices) the page was built from
  fields: () => fields,
  // the measured record: {analysis, identification} as the engine returned them, and whether busy
  record: () => ({ analysis: recordState.analysis, identification: recordState.identification, busy: Boolean(recordState.busy) }),
  // the ranges of the time plot's two y axes (x_M'' and z_M'' each on its own)
  // the bars of a spectrum plot ('plot-spec-x', 'plot-spec-z'): A_n [m/s^2], n = 0 ... N_MAX
  spectrum: (id) => plots[id] && Array.from(plots[id].data[1]),
  timeScales: () => plots.time && { ax: [plots.time.scales.ax.min, plots.time.scales.ax.max], az: [plots.time.scales.az.min, plots.time.scales.az.max], points: plots.time.data[0].length },
};

startWorker();
