// The engine runs here, off the page's thread: the page never freezes, whatever the case costs.
// Messages in:  {type: 'run', seq, values, n_max}  (values: field key -> number, as in fields())
// Messages out: {type: 'ready', fields, soilKeys, version}   (soilKeys: soil.input name -> the
//               soil keys it reads, by the engine's key_in_effect)
//               {type: 'result', seq, result, errors, ms}   (errors: key -> message)
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
  postMessage({ type: 'ready', fields, soilKeys, version: m.version() });
});

function run(msg) {
  const errors = {};
  for (const [key, value] of Object.entries(msg.values)) {
    const e = engine.checkField(key, value);
    if (e) errors[key] = e;
  }
  if (Object.keys(errors).length) {
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

onmessage = (ev) => {
  ready.then(() => {
    const msg = ev.data;
    if (msg.type === 'run') run(msg);
  });
};
