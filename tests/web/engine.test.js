// The WebAssembly engine (web/dist/oscidrum.js) against the native build: the same C++ sources
// must give the same metrics. For each case the native CLI runs it (`oscidrum run --format json`)
// and the WebAssembly engine runs the very parameters the CLI reports, under node.
//
// Usage: node engine.test.js <path to the native oscidrum> <web/dist>
'use strict';
const assert = require('node:assert/strict');
const { execFileSync } = require('node:child_process');
const fs = require('node:fs');
const path = require('node:path');

const [cli, dist] = process.argv.slice(2);
if (!cli || !dist) {
  console.error('usage: node engine.test.js OSCIDRUM_CLI WEB_DIST');
  process.exit(2);
}
if (!fs.existsSync(path.join(dist, 'oscidrum.wasm'))) {
  console.error(`${dist}/oscidrum.wasm not found: build it with scripts/build-web.sh`);
  process.exit(process.env.OSCIDRUM_WEB_REQUIRED ? 1 : 77);  // 77: ctest's SKIP_RETURN_CODE
}

// Relative agreement asked of every metric and harmonic (each on its own scale, metricFloor).
// Both builds run the same sources in IEEE double precision; what differs is the C library (glibc
// natively, musl's libm in Emscripten), whose sin, cos, exp may round differently in the last bit.
// The test also measures, and prints, how much the native metrics move when roller.M0, roller.m
// or roller.I change by one unit in the last place (the native build's own rounding band, about
// 1e-13 ... 1e-12 with the steady state solved for by shooting): the two builds agree about as
// closely as the native build agrees with itself.
const RTOL = 1e-12;

// The cases: the paper's default, stick-slip with the driving torque, pure rolling on stiff soil,
// and the log-spiral trough, at the default tolerances; then two at rtol 1e-12 (with the default
// atol 1e-11). Steady states by shooting, the default: a fixed point of the period map is a smooth
// function of the inputs, where the end of a transient is not (with the transient method pure
// rolling at G 40 is detected a period earlier or later after a last-bit change, 4e-8).
const tight = ['--set', 'numerics.method=shooting', '--set', 'numerics.rtol=1e-12'];
const cases = [
  { name: 'default (G 25, mu 0.5)', args: [] },
  { name: 'stick-slip, MMd = 0.05 M0', args: ['--MMd-fraction', '0.05'] },
  { name: 'pure rolling, G 40', args: ['--G', '40', '--pure-rolling'] },
  { name: 'spiral trough k 0.002, a 0.601, G 5', args: ['--k', '0.002', '--a', '0.601', '--G', '5'] },
  { name: 'pure rolling, G 40, shooting, rtol 1e-12', args: ['--G', '40', '--pure-rolling', ...tight] },
  { name: 'stick-slip, MMd = 0.05 M0, shooting, rtol 1e-12', args: ['--MMd-fraction', '0.05', ...tight] },
  // The vibratory drum of examples/vibratory.toml (partial uplift: flight phases, lift-offs and
  // landings), the explorer's second roller; its excitation is roller.static_moment, not M0.
  { name: 'vibratory drum, examples/vibratory.toml', args: [path.resolve(__dirname, '../../examples/vibratory.toml')],
    band: ['roller.static_moment', 'roller.m', 'roller.I'], extra: ['kb', 'cmv', 'rmv', 'flight_fraction', 'liftoffs_per_period', 'landing_velocity'] },
];

// |a - b| <= RTOL * scale, scale = max(|a|, |b|, floor): the floor is the size of the quantity
// the value belongs to (e.g. the largest harmonic of a signal), so numerical noise in a harmonic
// that is zero by symmetry is compared on the scale of the signal, not on its own.
// The tolerance of a case: RTOL, or twice the native build's rounding band where the case is that
// sensitive to a last-bit change (pure rolling at rtol 1e-12 moves by 1e-12 natively: the two
// C libraries' last bits move it as much).
let tolerance = RTOL;

// A metric that is undefined (NaN in the WebAssembly build, null in the native JSON: e.g. the
// vibratory drum's phi_lag, which lags no oscillating torque) must be undefined in both.
const absent = (v) => v === null || v === undefined || Number.isNaN(v);

function close(what, a, b, floor = 0) {
  if (absent(a) || absent(b)) {
    if (absent(a) && absent(b)) return 0;
    throw new assert.AssertionError({ message: `${what}: WebAssembly ${a} vs native ${b} (one undefined)` });
  }
  const scale = Math.max(Math.abs(a), Math.abs(b), floor);
  const diff = Math.abs(a - b);
  const rel = scale > 0 ? diff / scale : 0;
  if (!(diff <= tolerance * scale)) {
    throw new assert.AssertionError({
      message: `${what}: WebAssembly ${a} vs native ${b} (relative ${rel.toExponential(2)} > ${tolerance.toExponential(2)})`,
    });
  }
  return rel;
}

// |A exp(i theta) - B exp(i phi)|
function complexDiff(A, theta, B, phi) {
  return Math.hypot(A * Math.cos(theta) - B * Math.cos(phi), A * Math.sin(theta) - B * Math.sin(phi));
}

const METRICS = ['ddx_max', 'ddx_min', 'ddz_max', 'ddz_min', 'delta_max', 'delta_min', 'phi_lag',
                 'phi_amplitude', 'psi_xz', 'area', 'stick_fraction', 'slip_positive_fraction',
                 'slip_negative_fraction'];

// The scale a metric's difference is measured on, below which its own size does not go (as for
// the harmonics, the size of the quantity the value belongs to): phase fractions are shares of
// the period (scale 1); a peak belongs to its signal, so the largest and smallest value of
// x_M'', z_M'' and delta are both compared on the larger of their two sizes (delta_min = 0.003
// rad of a delta swinging up to 0.13 rad with the driving torque is 2 % of its signal); phase
// angles have no natural zero, so their difference is taken in absolute terms, on the scale of
// half a turn (psi_xz in rad: pi; phi_lag in units of pi rad: 1), as the phases of the harmonics
// are (through their complex coefficients). Relative to its own value, a lag near 0
// (psi_xz = -0.0046 rad on the spiral trough) would turn a difference of 1e-14 rad into 2e-12.
function metricFloor(key, metrics) {
  if (key.endsWith('_fraction') || key === 'phi_lag') return 1;
  if (key === 'psi_xz') return Math.PI;
  const peak = key.match(/^(.*)_(max|min)$/);
  if (peak) return Math.max(Math.abs(metrics[`${peak[1]}_max`]), Math.abs(metrics[`${peak[1]}_min`]));
  return 0;
}

// The next double above x (one unit in the last place).
function nextUp(x) {
  const b = new DataView(new ArrayBuffer(8));
  b.setFloat64(0, x);
  b.setBigUint64(0, b.getBigUint64(0) + 1n);
  return b.getFloat64(0);
}

function runNative(args) {
  return JSON.parse(execFileSync(cli, ['run', '--format', 'json', ...args], { encoding: 'utf8' }));
}

// The largest relative change of a scalar metric of the native build when roller.M0, roller.m
// or roller.I (the keys `keys`) change by one unit in the last place.
function roundingBand(native, args, keys = ['roller.M0', 'roller.m', 'roller.I']) {
  let band = 0;
  for (const key of keys) {
    const value = nextUp(native.parameters[key]);
    const p = runNative([...args, '--set', `${key}=${value.toPrecision(17)}`]);
    assert.equal(p.parameters[key], value);
    for (const m of METRICS) {
      if (absent(native.metrics[m])) continue;  // undefined: no rounding band
      const scale = Math.max(metricFloor(m, native.metrics), Math.abs(native.metrics[m]));
      if (scale > 0) band = Math.max(band, Math.abs(p.metrics[m] - native.metrics[m]) / scale);
    }
    for (const signal of ['ddx_harmonics', 'ddz_harmonics']) {
      const h0 = native.metrics[signal], h1 = p.metrics[signal];
      const largest = Math.max(...h0.map((h) => h.amplitude));
      h0.forEach((h, i) => {
        band = Math.max(band, complexDiff(h1[i].amplitude, h1[i].phase, h.amplitude, h.phase) / largest);
      });
    }
  }
  return band;
}

// A record as a logger writes it: a UTF-8 byte-order mark, 'Time [s]', the accelerations in g and
// z positive up (the model's z_M'' is positive down).
function recordCsv(rec) {
  const g = 9.80665;
  const lines = ['\ufeffTime [s],acc_x [g],acc_z [g]'];
  for (let i = 0; i < rec.t.length; i++) lines.push(`${rec.t[i].toPrecision(10)},${(rec.ddx_M[i] / g).toPrecision(10)},${(-rec.ddz_M[i] / g).toPrecision(10)}`);
  return lines.join('\n') + '\n';
}

async function main() {
  const createOscidrum = require(path.resolve(dist, 'oscidrum.js'));
  const engine = await createOscidrum({ wasmBinary: fs.readFileSync(path.join(dist, 'oscidrum.wasm')) });
  let failures = 0;
  for (const c of cases) {
    const native = runNative(c.args);
    const band = roundingBand(native, c.args, c.band);
    tolerance = Math.max(RTOL, 2 * band);
    const web = engine.simulate(native.parameters, native.metrics.ddx_harmonics.length - 1);
    let worst = 0;
    try {
      assert.equal(web.ok, true, web.error);
      assert.equal(web.status, native.status);
      assert.equal(web.diagnostics.multiplicity, native.diagnostics.multiplicity);
      const n = native.metrics, w = web.metrics;
      // The page has every metric the native run reports (both come from the output table).
      assert.deepEqual(Object.keys(w).sort(), Object.keys(n).sort());
      for (const key of [...METRICS, ...(c.extra || [])]) {
        worst = Math.max(worst, close(key, w[key], n[key], metricFloor(key, n)));
      }
      for (const signal of ['ddx_harmonics', 'ddz_harmonics']) {
        const nat = n[signal];
        const largest = Math.max(...nat.map((h) => h.amplitude));
        assert.equal(w[signal].amplitude.length, nat.length);
        nat.forEach((h, i) => {
          // Each harmonic as the complex coefficient A_n exp(i theta_n), on the scale of the
          // largest harmonic (a harmonic that is zero by symmetry carries only noise, and its
          // phase alone means nothing).
          const d = complexDiff(w[signal].amplitude[i], w[signal].phase[i], h.amplitude, h.phase);
          worst = Math.max(worst, close(`${signal}[${i}]`, d, 0, largest));
        });
      }
      console.log(`ok   ${c.name}: area ${w.area} m^2/s^4, worst relative difference ${worst.toExponential(2)} ` +
                  `(native rounding band ${band.toExponential(2)})`);
    } catch (e) {
      failures += 1;
      console.log(`FAIL ${c.name}: ${e.message} (native rounding band ${band.toExponential(2)})`);
    }
  }
  tolerance = RTOL;
  // Bad input is an error object with the library's message, never an abort.
  const bad = engine.simulate({ 'soil.G': -5e6, 'soil.input': 'modulus' }, 10);
  assert.equal(bad.ok, false);
  assert.match(bad.error, /soil\.G must be in \[10000, 1e\+11\]/);
  assert.equal(bad.key, 'soil.G');  // the error carries its key
  assert.equal(engine.keyInEffect({ 'soil.input': 'table2' }, 'soil.nu'), false);
  assert.equal(engine.keyInEffect({ 'soil.input': 'modulus' }, 'soil.nu'), true);
  const typo = engine.simulate({ 'soil.g': 1 }, 10);
  assert.match(typo.error, /did you mean 'soil\.G'/);
  // ... and the module still works afterwards.
  assert.equal(engine.simulate({}, 10).status, 'steady_state');
  // The field table is the library's: every key of the native parameters is there.
  const keys = engine.fields().map((f) => f.key);
  assert.deepEqual(keys, Object.keys(JSON.parse(execFileSync(cli, ['run', '--format', 'json'], { encoding: 'utf8' })).parameters));
  // Table 2 and Appendix B agree with the native `oscidrum soil`.
  for (const G of [5, 25, 70]) {
    const soil = JSON.parse(execFileSync(cli, ['soil', '--G', String(G), '--format', 'json'], { encoding: 'utf8' }));
    const row = soil.rows[0];
    const web = engine.soilCoefficients(row.G, row.nu, row.rho, {});
    assert.equal(web.ok, true, web.error);
    for (const k of ['a0', 'ksh', 'ksv', 'csh', 'csv']) close(`Appendix B ${k} at G ${G}`, web[k], row.formula[k]);
    const t2 = engine.table2().find((r) => r.G === row.G);
    for (const k of ['a0', 'ksh', 'ksv', 'csh', 'csv']) assert.equal(t2[k], row.table2[k], `Table 2 ${k} at G ${G}`);
    assert.equal(engine.table2Soil(row.G)['soil.ksh'], row.table2.ksh);
  }
  assert.equal(engine.table2().length, 14);
  assert.equal(engine.table2Soil(12e6).ok, false);
  assert.equal(engine.soilCoefficients(25e6, 0.6, 1900, {}).ok, false);
  console.log('ok   Table 2, Appendix B, field table, bad input');

  // A measured record (issue 25 point 4): the engine's synthetic record of a known soil written as
  // a logger would (a UTF-8 byte-order mark, 'Time [s]', accelerations in g, z positive up) is
  // read, analysed and identified by the WebAssembly engine as the native `oscidrum analyze` and
  // `oscidrum identify --window 0` do: one reader, one analysis, one identification.
  {
    const kF = 39 * 1.01;  // 1 % away from the case's f: M0 follows (5)
    const truth = { 'soil.input': 'modulus', 'soil.G': 30e6, 'roller.f': kF, 'roller.M0': 54947 * (kF / 39) ** 2 };
    const rec = engine.syntheticRecord(truth, { duration: 1, sample_rate: 1000, noise: 0.02, seed: 3 });
    assert.equal(rec.ok, true, rec.error);
    const csv = recordCsv(rec);
    const file = path.join(fs.mkdtempSync(path.join(require('node:os').tmpdir(), 'oscidrum-record-')), 'record.csv');
    fs.writeFileSync(file, csv);
    const options = { z_positive: 'up' };
    const a = engine.analyzeRecord(csv, 'record.csv', options);
    assert.equal(a.ok, true, a.error);
    const na = JSON.parse(execFileSync(cli, ['analyze', file, '--z-positive', 'up', '--format', 'json'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
    assert.equal(a.valid, na.valid);
    assert.equal(a.reading.t_column, 'Time [s]');  // the byte-order mark is not part of it
    assert.equal(a.reading.z_factor, -9.80665);
    assert.deepEqual([a.reading.t_column, a.reading.x_column, a.reading.z_column],
      [na.reading.t.column, na.reading.ddx_M.column, na.reading.ddz_M.column]);
    close('record f', a.f, na.f);
    for (const key of ['area', 'ddx_max', 'ddz_min', 'residual_x', 'residual_z']) close(`record ${key}`, a.metrics[key], na[key], 1e-3);
    na.ddz_harmonics.forEach((h, i) => close(`record ddz_harmonics[${i}]`, a.metrics.ddz_harmonics.amplitude[i], h.amplitude, 1e-3));
    const id = engine.identifyRecord(csv, 'record.csv', options, { 'soil.input': 'modulus' }, 'formulas');
    assert.equal(id.ok, true, id.error);
    assert.equal(id.valid, true, id.reason);
    const ni = JSON.parse(execFileSync(cli, ['identify', file, '--window', '0', '--z-positive', 'up', '--set', 'soil.input=modulus',
      '--format', 'json', '--quiet'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] })).windows[0];
    const G = id.estimates[0], nG = ni.estimates[0];
    assert.equal(G.name, 'G');
    // The identification iterates on simulations (model tolerance 1e-6): the two builds agree
    // far below the estimate's own uncertainty.
    for (const k of ['value', 'lower', 'upper']) assert.ok(Math.abs(G[k] - nG[k]) <= 1e-6 * nG[k], `G ${k}: ${G[k]} vs native ${nG[k]}`);
    assert.ok(G.lower <= 30e6 && 30e6 <= G.upper, `G = ${G.value} [${G.lower}, ${G.upper}] misses the truth 30e6`);
    // The conventions are options: the same record read with z positive down is another record.
    const down = engine.analyzeRecord(csv, 'record.csv', { z_positive: 'down' });
    assert.equal(down.reading.z_factor, 9.80665);
    // Bad options and bad text: messages naming the option or the line, never an abort.
    assert.match(engine.analyzeRecord(csv, 'record.csv', { units: 'furlongs' }).error, /record option units must be one of auto, m\/s2, g, mg; got 'furlongs'/);
    assert.match(engine.analyzeRecord('Time [s],acc_x [g],acc_z [g]\n0,1,x\n', 'bad.csv', {}).error, /bad\.csv:2: column 'acc_z \[g\]' must be a number; got 'x'/);
    assert.match(engine.analyzeRecord('a,b,c\n0,1,2\n', 'bad.csv', {}).error, /no column looks like the time/);
    console.log(`ok   record: f ${a.f} Hz, area ${a.metrics.area}, G ${G.value} [${G.lower}, ${G.upper}] (native ${nG.value}); bad records and options`);
  }
  if (failures) process.exit(1);
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
