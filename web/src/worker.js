// The engine runs here, off the page's thread: the page never freezes, whatever the case costs.
// Messages in:  {type: 'run', seq, values, n_max}  (values: field key -> number, as in fields())
// Messages out: {type: 'ready', fields, table2, version}
//               {type: 'result', seq, result, errors, soil, ms}   (errors: key -> message;
//               soil: the Appendix B coefficients when soil.input is modulus)
'use strict';
importScripts('oscidrum.js');

let engine = null;
const ready = createOscidrum().then((m) => {
  engine = m;
  const fields = m.fields();
  // Warm the engine up (the browser compiles the hot code fully after a first run).
  m.simulate({}, 10);
  postMessage({ type: 'ready', fields, table2: m.table2(), version: m.version() });
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
  const v = msg.values;
  const soil = v['soil.input'] === 1 ? engine.soilCoefficients(v['soil.G'], v['soil.nu'], v['soil.rho'], v) : null;
  const t0 = performance.now();
  const result = engine.simulate(msg.values, msg.n_max);
  const ms = performance.now() - t0;
  const transfer = [];
  if (result.ok) for (const v of Object.values(result.samples)) transfer.push(v.buffer);
  postMessage({ type: 'result', seq: msg.seq, result, errors, soil, ms }, transfer);
}

onmessage = (ev) => {
  ready.then(() => {
    const msg = ev.data;
    if (msg.type === 'run') run(msg);
  });
};
