// The engine runs here, off the page's thread: the page never freezes, whatever the case costs.
// Messages in:  {type: 'run', seq, values, n_max, checkOnly}  (values: field key -> number, as in
//               fields(); checkOnly: only check every value against its field's rule)
//               {type: 'record', seq, text, name, options, values, soilScale}: a measured record
//               (its CSV text; options: units, x_positive, z_positive as `oscidrum analyze`)
// Messages out: {type: 'ready', fields, soilKeys, rollerKeys, version}   (soilKeys: soil.input
//               name -> the soil keys it reads; rollerKeys: roller.type name -> the keys that
//               take effect with that roller and not with every roller (roller.M0 for the
//               oscillation drum, roller.static_moment for the vibratory one); both by the
//               engine's key_in_effect)
//               {type: 'result', seq, result, errors, ms}   (errors: key -> message)
//               {type: 'record-analysis', seq, analysis, ms}   (the engine's analyzeRecord)
//               {type: 'record-identification', seq, identification, ms}   (identifyRecord)
'use strict';
importScripts('oscidrum.js');

let engine = null;
const ready = createOscidrum().then((m) => {
  engine = m;
  const fields = m.fields();
  // Warm the engine up (the browser compiles the hot code fully after a first run).
  m.simulate({}, 10);
  const soilKeys = {};
  for (const choice of fields.find((f) => f.key === 'soil.input').choices) {
    soilKeys[choice] = fields.filter((f) => f.key.startsWith('soil.') && f.key !== 'soil.input' &&
                                            m.keyInEffect({ 'soil.input': choice }, f.key)).map((f) => f.key);
  }
  // The keys of one roller only: in effect with some roller.type (under some soil input) and not
  // with another. (Under the default Table 2 soil alone, roller.b, which Appendix B reads, was
  // taken for the vibratory drum's only and hidden for the oscillation drum on a modulus soil.)
  const rollers = fields.find((f) => f.key === 'roller.type').choices;
  const soils = fields.find((f) => f.key === 'soil.input').choices;
  const inEffect = Object.fromEntries(rollers.map((choice) => [choice,
    new Set(fields.filter((f) => soils.some((soil) => m.keyInEffect({ 'roller.type': choice, 'soil.input': soil }, f.key)))
      .map((f) => f.key))]));
  const rollerKeys = {};
  for (const choice of rollers) {
    rollerKeys[choice] = [...inEffect[choice]].filter((key) => rollers.some((other) => !inEffect[other].has(key)));
  }
  postMessage({ type: 'ready', fields, soilKeys, rollerKeys, version: m.version() });
});

function run(msg) {
  const errors = {};
  for (const [key, value] of Object.entries(msg.values)) {
    const e = engine.checkField(key, value);
    if (e) errors[key] = e;
  }
  if (msg.checkOnly) {
    // The rules of several fields too, on the values valid on their own (the others at their
    // defaults): an R below the drum radius beside an empty G is flagged with it.
    const valid = Object.fromEntries(Object.entries(msg.values).filter(([key]) => !errors[key]));
    const broken = engine.checkCase(valid);
    if (broken && broken.key && !errors[broken.key]) errors[broken.key] = broken.error;
  }
  if (Object.keys(errors).length || msg.checkOnly) {
    postMessage({ type: 'result', seq: msg.seq, result: null, errors, ms: 0 });
    return;
  }
  const t0 = performance.now();
  const result = engine.simulate(msg.values, msg.n_max);
  const ms = performance.now() - t0;
  const transfer = [];
  // The sample columns travel without a copy (their buffers are transferred; `columns` is copied).
  if (result.ok) for (const v of Object.values(result.samples)) if (ArrayBuffer.isView(v)) transfer.push(v.buffer);
  postMessage({ type: 'result', seq: msg.seq, result, errors, ms }, transfer);
}

// A measured record: read and analysed (f, harmonics, figure, area) as `oscidrum analyze` does,
// posted, then the soil identified from it as `oscidrum identify --window 0` does (seconds).
// Nothing leaves the browser: the text came from a file the user dropped or picked.
function record(msg) {
  let t0 = performance.now();
  const analysis = engine.analyzeRecord(msg.text, msg.name, msg.options);
  postMessage({ type: 'record-analysis', seq: msg.seq, analysis, ms: performance.now() - t0 });
  if (!analysis.ok) return;
  t0 = performance.now();
  const identification = engine.identifyRecord(msg.text, msg.name, msg.options, msg.values, msg.soilScale);
  postMessage({ type: 'record-identification', seq: msg.seq, identification, ms: performance.now() - t0 });
}

onmessage = (ev) => {
  ready.then(() => {
    const msg = ev.data;
    if (msg.type === 'run') run(msg);
    else if (msg.type === 'record') record(msg);
  });
};
