// End-to-end test of the explorer in headless Chromium (Debian's chromium, driven by
// playwright-core): load the page from a local static server on 127.0.0.1, wait for its ready
// marker and the default case, change G and mu, check that the displayed area and status are
// those of the native engine, that z_M'' has its own axis and the area caption stays off the
// figure, that the largest harmonics are listed with their n, that a case without a steady state
// shows its status and message, that a measured record dropped onto the page is drawn and its
// soil identified, that scripts/screenshot-web.sh captures a case, that bad input (empty, NaN,
// out of range; several at once) shows a message next to each input without freezing the page,
// that the exported TOML runs natively to the same area, that the roller selector runs the
// vibratory drum of examples/vibratory.toml as the native engine does (with its own inputs and
// rows, none of the oscillation drum's), draws the vertical exciter's x_M'' of round-off as absent
// (flat on zero, no spectrum bars, said so) and restores the oscillation drum's default case,
// that no console error occurred, and save a screenshot.
//
// Usage: node e2e.test.js <path to the native oscidrum> <web/dist> <screenshot.png>
// (OSCIDRUM_KEEP_EXPORTS=DIR keeps the downloaded exports in DIR.)
'use strict';
const assert = require('node:assert/strict');
const { execFileSync, spawn } = require('node:child_process');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');

const [cli, dist, screenshot] = process.argv.slice(2);
const CHROMIUM = process.env.OSCIDRUM_CHROMIUM || '/usr/bin/chromium';
const webDir = path.resolve(__dirname, '../../web');

function skip(why) {
  console.error(why);
  process.exit(process.env.OSCIDRUM_WEB_REQUIRED ? 1 : 77);  // 77: ctest's SKIP_RETURN_CODE
}
if (!fs.existsSync(path.join(dist || '', 'oscidrum.wasm'))) skip(`${dist}/oscidrum.wasm not found: build it with scripts/build-web.sh`);
if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} not found (apt-get install chromium)`);
let chromium;
try {
  ({ chromium } = require(path.join(webDir, 'node_modules', 'playwright-core')));
} catch {
  skip('playwright-core not installed: run scripts/build-web.sh (npm ci in web/)');
}

// The area the displayed value must match: the page shows the WebAssembly engine's full double,
// which agrees with the native build within the native build's own rounding band (see
// engine.test.js: at most about 1e-10 relative for these stick-slip cases).
const AREA_RTOL = 1e-9;

function native(args) {
  return JSON.parse(execFileSync(cli, ['run', '--format', 'json', ...args], { encoding: 'utf8' }));
}

// A record of the soil G [Pa] (Appendix B) by the WebAssembly engine (synthetic_record), 1 % above
// 39 Hz, 2 % noise, as a logger would write it: a UTF-8 byte-order mark, 'Time [s]', the
// accelerations in g, z positive up.
async function recordCsv(distDir, G) {
  const createOscidrum = require(path.resolve(distDir, 'oscidrum.js'));
  const engine = await createOscidrum({ wasmBinary: fs.readFileSync(path.join(distDir, 'oscidrum.wasm')) });
  const f = 39 * 1.01;
  const rec = engine.syntheticRecord({ 'soil.input': 'modulus', 'soil.G': G, 'roller.f': f, 'roller.M0': 54947 * (f / 39) ** 2 },
    { duration: 1, sample_rate: 1000, noise: 0.02, seed: 3 });
  assert.equal(rec.ok, true, rec.error);
  const g = 9.80665;
  const lines = ['\ufeffTime [s],acc_x [g],acc_z [g]'];
  for (let i = 0; i < rec.t.length; i++) lines.push(`${rec.t[i].toPrecision(10)},${(rec.ddx_M[i] / g).toPrecision(10)},${(-rec.ddz_M[i] / g).toPrecision(10)}`);
  return lines.join('\n') + '\n';
}

function startServer() {
  return new Promise((resolve, reject) => {
    const server = spawn(process.execPath, [path.join(webDir, 'serve.js'), '--port', '0', '--dir', dist], { stdio: ['ignore', 'pipe', 'inherit'] });
    server.stdout.on('data', (d) => {
      const m = /http:\/\/127\.0\.0\.1:\d+\//.exec(String(d));
      if (m) resolve({ server, url: m[0] });
    });
    server.on('exit', (code) => reject(new Error(`server exited with ${code}`)));
  });
}

async function main() {
  const { server, url } = await startServer();
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'oscidrum-chromium-'));
  let browser = null;
  const consoleErrors = [];
  try {
    // a fresh profile (--user-data-dir) for every run
    browser = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      viewport: { width: 1400, height: 1150 },
      args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
        '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    });
    const page = browser.pages()[0] || await browser.newPage();
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(String(e.stack || e)));
    // Only the local server: any other request would mean the page is not self-contained.
    const foreign = [];
    page.on('request', (req) => { if (!req.url().startsWith(url) && !req.url().startsWith('blob:') && !req.url().startsWith('data:')) foreign.push(req.url()); });

    const settled = async () => {
      await page.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 30000 });
      return page.evaluate(() => ({
        status: document.getElementById('status').dataset.value,
        statusText: document.getElementById('status').textContent,
        area: Number(document.getElementById('area-caption').dataset.value),
      }));
    };
    const setInput = async (name, text) => {
      await page.fill(`[id="in-${name}"]`, text);
    };
    const errorOf = (name) => page.textContent(`[id="err-${name}"]`);

    await page.goto(url);
    // The ready marker (issue 25 point 5): set once the first case is shown, for screenshots.
    await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
    assert.doesNotMatch(await page.textContent('#status'), /loading/);
    let shown = await settled();
    const def = native([]);
    assert.equal(shown.status, def.status);
    assert.ok(Math.abs(shown.area - def.metrics.area) <= AREA_RTOL * def.metrics.area, `default area ${shown.area} vs native ${def.metrics.area}`);
    console.log(`ok   default case: ${shown.status}, area ${shown.area}`);

    // Change G (Table 2) and mu: the page must show what the native engine gives.
    await setInput('G', '40');
    await setInput('mu', '0.3');
    await page.waitForFunction(() => location.search.includes('mu=0.3') && location.search.includes('G=40'));
    shown = await settled();
    const changed = native(['--G', '40', '--mu', '0.3']);
    assert.equal(shown.status, changed.status);
    assert.ok(Math.abs(shown.area - changed.metrics.area) <= AREA_RTOL * changed.metrics.area, `G 40 mu 0.3: area ${shown.area} vs native ${changed.metrics.area}`);
    assert.ok(Math.abs(shown.area - def.metrics.area) > 1e-3 * def.metrics.area, 'the area did not change');
    console.log(`ok   G 40, mu 0.3: ${shown.status}, area ${shown.area} (native ${changed.metrics.area})`);
    // z_M'' (about +-1 m/s^2) has its own axis in the time plot (issue 25 point 2): its scale
    // spans its own values, not x_M'''s (about +-12), so it is not a flat line.
    {
      const sc = await page.evaluate(() => window.explorer.timeScales());
      const zr = [changed.metrics.ddz_min, changed.metrics.ddz_max], xr = [changed.metrics.ddx_min, changed.metrics.ddx_max];
      assert.ok(sc.az[0] <= zr[0] && zr[1] <= sc.az[1] && sc.ax[0] <= xr[0] && xr[1] <= sc.ax[1], JSON.stringify(sc));
      assert.ok(zr[1] - zr[0] >= 0.5 * (sc.az[1] - sc.az[0]), `z_M'' fills less than half of its axis: ${JSON.stringify(sc)}`);
      assert.ok(sc.az[1] - sc.az[0] < 0.5 * (sc.ax[1] - sc.ax[0]), `z_M'' on the axis of x_M'': ${JSON.stringify(sc)}`);
      // The area caption sits above the figure-eight, not on it.
      const fig = await page.evaluate(() => ({ ...document.getElementById('plot-figure').dataset }));
      assert.ok(Number(fig.captionBottom) < Number(fig.curveTop), `the area caption covers the figure: ${JSON.stringify(fig)}`);
      console.log(`ok   z_M'' on its own axis [${sc.az.map((v) => v.toFixed(2))}] beside x_M'' [${sc.ax.map((v) => v.toFixed(2))}]; the caption ends at ${fig.captionBottom} px, the figure starts at ${Number(fig.curveTop).toFixed(1)} px`);
    }
    // A valid case without a steady state shows its status and message and draws its last
    // periods (not "invalid input").
    {
      const page3 = await browser.newPage();
      page3.on('pageerror', (e) => consoleErrors.push(String(e.stack || e)));
      await page3.goto(url + '?soil=modulus&G=1&mu=0.8&MMd=0.3');
      await page3.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 60000 });
      const status = await page3.evaluate(() => document.getElementById('status').textContent);
      let nat;  // exit code 1: not a steady state; its JSON is on stdout all the same
      try {
        nat = native(['--set', 'soil.input=modulus', '--set', 'soil.G=1e6', '--mu', '0.8', '--MMd-fraction', '0.3']);
      } catch (e) {
        nat = JSON.parse(String(e.stdout));
      }
      assert.notEqual(nat.status, 'steady_state');
      assert.ok(status.startsWith(`${nat.status}: `), `status shown: '${status}' (native ${nat.status})`);
      assert.ok(!status.includes('invalid input'), status);
      assert.ok(status.includes(nat.message.slice(0, 20)), `the message is not shown: '${status}' (native '${nat.message}')`);
      // Its periods are drawn as the CLI samples them: none for a run that stops (the drum
      // spins: gross slip), so no plot of an earlier case stays; the last periods for a run
      // that reaches numerics.max_periods.
      assert.equal(nat.status, 'gross_slip');
      assert.equal(await page3.evaluate(() => window.explorer.timeScales()), undefined);
      await page3.goto(url + '?numerics.max_periods=3');
      await page3.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 60000 });
      const status3 = await page3.evaluate(() => document.getElementById('status').textContent);
      assert.match(status3, /^max_periods_reached: no steady state within numerics\.max_periods = 3 periods/);
      const sc = await page3.evaluate(() => window.explorer.timeScales());
      assert.ok(sc && sc.points > 100, `the last periods are not drawn: ${JSON.stringify(sc)}`);
      await page3.close();
      console.log(`ok   a case without a steady state: '${status.slice(0, 60)}...'`);
    }
    // From a probe of the page (2026-12-05): with roller.unbalance the driving torque is a
    // fraction of the unbalance's M0 = 4 m_u e_u e_w nu^2 (5), as --MMd-fraction takes it (the
    // page took the M0 box's 54947 N m: another area than the CLI's), and the M0 box is not in
    // effect; a period-2 steady state's time plot spans two of its periods (4 excitation periods);
    // hexadecimal text is not a number; a link's misspelled choice is said, not replaced quietly;
    // and while a case computes the status says so.
    {
      const page5 = await browser.newPage();
      page5.on('pageerror', (e) => consoleErrors.push(String(e.stack || e)));
      const ready = () => page5.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 60000 });
      await page5.goto(url + '?roller.unbalance=0.22877&f=50&MMd=0.05');
      await ready();
      const nat = native(['--set', 'roller.unbalance=0.22877', '--f', '50', '--MMd-fraction', '0.05']);
      const area = Number(await page5.getAttribute('#area-caption', 'data-value'));
      assert.ok(Math.abs(area - nat.metrics.area) <= AREA_RTOL * nat.metrics.area, `unbalance: area ${area} vs native ${nat.metrics.area}`);
      assert.equal(await page5.isDisabled('#in-M0'), true);
      const m0row = await page5.evaluate(() => [...document.querySelectorAll('#metrics tbody tr')].map((tr) => tr.textContent).find((t) => t.startsWith('M0, MMd')) || '');
      assert.match(m0row, /^M0, MMd90314\.8, 4515\.74/);
      // the disabled M0 box is not checked either (a bad text there blocked every run)
      await page5.goto(url + '?M0=abc&roller.unbalance=0.22877&f=50&MMd=0.05');
      await ready();
      assert.equal(Number(await page5.getAttribute('#area-caption', 'data-value')), area);
      await page5.goto(url + '?roller.type=vibratory&roller.exciter=circulr');
      await ready();
      assert.match(await page5.textContent('#url-note'), /roller\.exciter = 'circulr' is not one of circular/);
      // A link's parameter the case does not read is said (it was dropped without a word); the
      // drum width b, which Appendix B reads, is the oscillation drum's too on a modulus soil (it
      // was taken for the vibratory drum's only, hidden, and the page computed b = 1.68 m).
      await page5.goto(url + '?roller.type=vibratory&M0=1000');
      await ready();
      assert.match(await page5.textContent('#url-note'), /M0 = '1000' has no effect with this roller, soil and trough: ignored/);
      await page5.goto(url + '?soil=modulus&G=33&roller.b=2.5');
      await ready();
      assert.equal(await page5.textContent('#url-note'), '');
      assert.equal(await page5.evaluate(() => window.explorer.last().result.case['roller.b']), 2.5);
      // A field away from its default that the case does not read (v_eps under Coulomb's law).
      await page5.goto(url + '?contact.v_eps=5');
      await ready();
      assert.match(await page5.textContent('#effect-note'), /No effect in this case .*contact\.v_eps = 5/);
      // G's rule in the box's unit (the engine's message spoke of Pa beside an MN/m² box).
      await page5.goto(url + '?soil=modulus&G=0.001');
      await page5.waitForFunction(() => /invalid input/.test(document.getElementById('status').textContent), null, { timeout: 30000 });
      const gError = await page5.textContent('#err-G');
      assert.match(gError, /soil\.G must be in \[0\.01, 100000\] MN\/m.*; got 0\.001 MN\/m/);
      assert.doesNotMatch(gError, /values are in Pa/);
      await page5.goto(url + '?trough=spiral&k=0.002&a=0.601&f=25&roller.unbalance=0.22877&mu=0.7&soil=modulus&G=140');
      await ready();
      const sc = await page5.evaluate(() => window.explorer.timeScales());
      assert.equal(sc.points, 4 * 1024, `a period-2 orbit's two periods: ${JSON.stringify(sc)}`);
      await page5.goto(url + '?G=0x28&R=0.5&contact.law=regularized');
      await page5.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
      await page5.waitForFunction(() => /invalid input \(2 fields\)/.test(document.getElementById('status').textContent), null, { timeout: 30000 });
      assert.match(await page5.textContent('#err-G'), /not a number: '0x28'/);
      // a rule of two fields beside an input invalid on its own: both flagged at once
      assert.match(await page5.textContent('#err-R'), /trough\.a must be > roller\.r/);
      assert.match(await page5.textContent('#url-note'), /contact\.law = 'regularized' is not one of coulomb/);
      assert.equal(await page5.isDisabled('#export-toml'), true);
      await page5.fill('#in-G', '40');
      await page5.fill('#in-R', '0.606');
      await ready();
      const busy = await page5.evaluate(() => {
        const g = document.getElementById('in-G');
        g.value = '45';
        g.dispatchEvent(new Event('input', { bubbles: true }));
        const s = document.getElementById('status');
        return { text: s.textContent, cls: s.className, metrics: document.getElementById('metrics').classList.contains('stale') };
      });
      assert.match(busy.text, /^computing this case/);
      assert.equal(busy.cls, 'busy');
      assert.equal(busy.metrics, true);
      await ready();
      assert.equal(await page5.getAttribute('#status', 'class'), 'ok');
      // An invalid input leaves the earlier case's results faded, its samples not exported (its
      // table read 'steady_state' at full strength and its CSV was exported); a record read
      // then does not turn the status green nor the case file on again (it exported the last
      // valid case beside an invalid form).
      await page5.fill('#in-mu', '-1');
      await page5.waitForFunction(() => /invalid input/.test(document.getElementById('status').textContent), null, { timeout: 30000 });
      assert.equal(await page5.evaluate(() => document.getElementById('metrics').classList.contains('stale')), true);
      // The timing line beside the status is the earlier case's too.
      assert.equal(await page5.evaluate(() => document.getElementById('timing').classList.contains('stale')), true);
      assert.equal(await page5.isDisabled('#export-csv'), true);
      assert.equal(await page5.isDisabled('#export-toml'), true);
      await page5.setInputFiles('#record-file', { name: 'broken.csv', mimeType: 'text/csv', buffer: Buffer.from('t,ax,az\n0,1,2\n0.001,1,oops\n') });
      await page5.waitForFunction(() => /cannot read/.test(document.getElementById('record-status').textContent), null, { timeout: 30000 });
      assert.match(await page5.textContent('#status'), /invalid input/);
      assert.equal(await page5.getAttribute('#status', 'class'), 'bad');
      assert.equal(await page5.isDisabled('#export-toml'), true);
      assert.equal(await page5.isDisabled('#export-csv'), true);
      await page5.close();
      console.log('ok   the unbalance\'s M0 for MMd (area as native), a period-2 plot of 4 periods, 0x28 refused beside R < r (both flagged), a misspelled choice in the link said, "computing" while a case runs');
    }
    // A measured record (issue 25 point 4): a record of a known soil (G = 30 MN/m^2 by Appendix
    // B, f 1 % above the case's, 2 % noise) made by the engine and written as a logger would (a
    // byte-order mark, 'Time [s]', g, z positive up) is dropped onto the page: its fit is drawn
    // over the model and G is identified with a 95 % interval that holds the truth; a broken file
    // picked with the button shows the reader's message.
    {
      const G_TRUE = 30e6;
      const csv = await recordCsv(dist, G_TRUE);
      const page4 = await browser.newPage();
      page4.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
      page4.on('pageerror', (e) => consoleErrors.push(String(e.stack || e)));
      await page4.goto(url + '?soil=modulus');
      await page4.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
      await page4.selectOption('#record-z', 'up');
      await page4.evaluate((text) => {
        const dt = new DataTransfer();
        dt.items.add(new File([text], 'pass.csv', { type: 'text/csv' }));
        document.getElementById('results').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
      }, csv);
      await page4.waitForFunction(() => { const r = window.explorer.record(); return r.identification && !r.busy; }, null, { timeout: 60000 });
      const rec = await page4.evaluate(() => window.explorer.record());
      assert.equal(rec.analysis.ok, true, rec.analysis.error);
      assert.equal(rec.analysis.valid, true, rec.analysis.reason);
      assert.equal(rec.analysis.reading.t_column, 'Time [s]');
      assert.equal(rec.analysis.reading.z_factor, -9.80665);
      assert.ok(Math.abs(rec.analysis.f - 39 * 1.01) < 1e-3, `f ${rec.analysis.f}`);
      const id = rec.identification;
      assert.equal(id.ok && id.valid, true, id.error || id.reason);
      const G = id.estimates.find((e) => e.name === 'G');
      assert.ok(G.lower <= G_TRUE && G_TRUE <= G.upper, `G ${G.value} [${G.lower}, ${G.upper}] misses ${G_TRUE}`);
      assert.ok(G.upper - G.lower < 0.05 * G_TRUE, `the interval is not informative: [${G.lower}, ${G.upper}]`);
      const table = await page4.textContent('#record-table');
      assert.match(table, /identified G.*G = 30\.\d* ± [\d.]+ MN\/m²/);
      assert.match(table, /95 % interval \[/);
      const fig = await page4.evaluate(() => ({ ...document.getElementById('plot-figure').dataset }));
      assert.ok(Number(fig.measuredPoints) > 100, `the measured figure is not drawn: ${JSON.stringify(fig)}`);
      assert.equal(await page4.getAttribute('#record-status', 'data-value'), 'identified');
      // The picker, and a file the reader refuses: its message, naming the file and the line.
      await page4.setInputFiles('#record-file', { name: 'broken.csv', mimeType: 'text/csv', buffer: Buffer.from('t,ax,az\n0,1,2\n0.001,1,oops\n') });
      await page4.waitForFunction(() => /cannot read/.test(document.getElementById('record-status').textContent), null, { timeout: 30000 });
      assert.match(await page4.textContent('#record-status'), /broken\.csv:3: column 'az' must be a number; got 'oops'/);
      assert.equal(await page4.evaluate(() => document.getElementById('plot-figure').dataset.measuredPoints), '0');
      await page4.close();
      console.log(`ok   record dropped: f ${rec.analysis.f.toFixed(4)} Hz, G ${(G.value / 1e6).toFixed(3)} [${(G.lower / 1e6).toFixed(3)}, ${(G.upper / 1e6).toFixed(3)}] MN/m^2 (truth 30) in ${id.simulations} simulations; its figure drawn; a broken file picked shows the reader's message`);
    }
    // The screenshot script (issue 25 point 5) waits for the ready marker: what it captures is a
    // case, not "loading the engine...".
    {
      const png = path.join(profile, 'shot.png');
      const out = execFileSync('bash', [path.resolve(__dirname, '../../scripts/screenshot-web.sh'), 'G=40&mu=0.3', png],
        { encoding: 'utf8', env: { ...process.env, OSCIDRUM_WEB_DIST: dist } });
      assert.match(out, /steady state/, out);
      const head = fs.readFileSync(png);
      assert.equal(head.toString('latin1', 1, 4), 'PNG');
      assert.equal(head.readUInt32BE(16), 1400);  // IHDR width: the whole page
      console.log(`ok   scripts/screenshot-web.sh: ${out.trim()}`);
    }
    // The metrics table shows each signal's three largest harmonics with their n (issue 25
    // point 1), by the native amplitudes; with the driving torque MMd = 0.05 M0 they are z's A1
    // and x's A2, which fixed rows (x: A1, A3, A5; z: A2, A4, A6) hid.
    const rowText = (name) => page.evaluate((n) => [...document.querySelectorAll('#metrics tbody tr')]
      .map((tr) => tr.textContent).find((t) => t.includes(n)) || '', name);
    const checkHarmonics = async (nat) => {
      const shownTop = {};
      for (const [signal, key] of [["x_M'' largest harmonics", 'ddx_harmonics'], ["z_M'' largest harmonics", 'ddz_harmonics']]) {
        const amplitudes = nat.metrics[key].map((h) => h.amplitude);
        const top = amplitudes.map((a, n) => [a, n]).slice(1).sort((p, q) => q[0] - p[0]).slice(0, 3).map(([, n]) => n);
        const text = await rowText(signal);
        for (const n of top) assert.ok(text.includes(`A${n} = ${Number(amplitudes[n].toPrecision(4))}`), `${signal}: A${n} missing in '${text}'`);
        shownTop[key] = top;
      }
      return shownTop;
    };
    await checkHarmonics(changed);
    {
      await setInput('MMd', '0.05');
      await settled();
      const driven = native(['--G', '40', '--mu', '0.3', '--MMd-fraction', '0.05']);
      const top = await checkHarmonics(driven);
      assert.ok(top.ddz_harmonics.includes(1) && top.ddx_harmonics.includes(2), JSON.stringify(top));
      console.log(`ok   G 40, mu 0.3, MMd 0.05 M0: largest harmonics x ${top.ddx_harmonics}, z ${top.ddz_harmonics} shown with their n`);
      await setInput('MMd', '0');
      await settled();
    }

    // The exported TOML is a case file the native tool runs to the same result.
    const toml = await page.evaluate(() => window.explorer.caseToml());
    const tomlFile = path.join(profile, 'case.toml');
    fs.writeFileSync(tomlFile, toml);
    const fromToml = native([tomlFile]);
    assert.ok(Math.abs(fromToml.metrics.area - changed.metrics.area) <= 1e-14 * changed.metrics.area, 'TOML export runs to another area');
    const csv = await page.evaluate(() => window.explorer.steadyCsv());
    // The header is the native `run --csv` header, column for column (one output table).
    const nativeCsv = path.join(profile, 'native.csv');
    execFileSync(cli, ['run', '--quiet', '--G', '40', '--mu', '0.3', '--csv', nativeCsv]);
    assert.equal(csv.split('\n')[0], fs.readFileSync(nativeCsv, 'utf8').split('\n')[0]);
    assert.equal(csv.trim().split('\n').length - 1, changed.sampling ? changed.sampling.samples : 2048);
    const svg = await page.evaluate(() => window.explorer.plotsSvg());
    assert.match(svg, /^<svg [^>]*xmlns="http:\/\/www.w3.org\/2000\/svg"/);
    // The buttons download these files.
    for (const [button, name, start] of [['#export-toml', 'case.toml', '# oscidrum case'],
      ['#export-csv', 'steady_state.csv', 't[s],'], ['#export-svg', 'oscidrum-plots.svg', '<svg'],
      ['#export-png', 'oscidrum-plots.png', '\x89PNG']]) {
      const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
      assert.equal(download.suggestedFilename(), name);
      const file = path.join(profile, name);
      await download.saveAs(file);
      assert.equal(fs.readFileSync(file, 'latin1').slice(0, start.length), start, name);
      if (process.env.OSCIDRUM_KEEP_EXPORTS) fs.copyFileSync(file, path.join(process.env.OSCIDRUM_KEEP_EXPORTS, name));
    }
    console.log('ok   exports: TOML runs natively to the same area, CSV columns, SVG; the buttons download TOML, CSV, SVG, PNG');

    // A shared link restores the case.
    const link = page.url();
    const page2 = await browser.newPage();
    page2.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    await page2.goto(link);
    await page2.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 30000 });
    assert.equal(await page2.inputValue('#in-G'), '40');
    assert.equal(await page2.inputValue('#in-mu'), '0.3');
    assert.equal(Number(await page2.getAttribute('#area-caption', 'data-value')), shown.area);
    await page2.close();
    console.log('ok   the URL restores the case');

    // Bad input: a message next to the input, the page stays responsive, nothing is computed.
    const before = await page.evaluate(() => window.explorer.last().result);
    for (const [name, text, pattern] of [
      ['G', '', /enter a value/],
      ['mu', 'abc', /not a number/],
      ['mu', 'NaN', /not a number/],
      ['mu', '-0.2', /contact\.mu must be >= 0/],
      ['kd', '1e999', /finite/],
      ['G', '12', /soil\.G must be a G of paper Table 2/],
      ['R', '0.5', /trough/],
      // a field of the table without its own input ('more parameters')
      ['x:roller.r', '-1', /roller\.r must be > 0/],
      ['x:numerics.samples_per_period', '8', /numerics\.samples_per_period must be/],
      // an integer key takes digits only, as in a case file and --set
      ['x:numerics.max_periods', '1e3', /not an integer \(digits only\): '1e3'; numerics\.max_periods/],
      ['x:numerics.max_periods', '5.0', /not an integer \(digits only\)/],
    ]) {
      if (name.startsWith('x:')) await page.click('summary');
      const good = await page.inputValue(`[id="in-${name}"]`);
      await setInput(name, text);
      await page.waitForFunction((n) => document.getElementById(`err-${n}`).textContent !== '', name, { timeout: 10000 });
      const msg = await errorOf(name);
      assert.match(msg, pattern, `input ${name} = '${text}'`);
      assert.equal(await page.evaluate(() => document.getElementById('status').className), 'bad');
      // responsive: a round trip through the page's event loop is immediate
      const t0 = Date.now();
      await page.evaluate(() => new Promise((r) => setTimeout(r, 0)));
      assert.ok(Date.now() - t0 < 1000, 'the page froze');
      console.log(`ok   ${name} = '${text}': "${msg}"`);
      await setInput(name, good);
      if (name.startsWith('x:')) await page.click('summary');
      await page.waitForFunction((n) => document.getElementById(`err-${n}`).textContent === '', name);
      await settled();
    }
    const after = await page.evaluate(() => window.explorer.last().result);
    assert.equal(after.metrics.area, before.metrics.area);
    // Every invalid input at once (issue 25 point 3), not only the first: an empty G and a
    // non-numeric f (the page's parsing) beside a negative mu and cd (the engine's rules).
    {
      const bad = { G: '', f: 'abc', mu: '-0.2', cd: '-1' };
      const good = {};
      for (const [name, text] of Object.entries(bad)) {
        good[name] = await page.inputValue(`[id="in-${name}"]`);
        await setInput(name, text);
      }
      await page.waitForFunction(() => document.getElementById('err-mu').textContent !== '' && document.getElementById('err-cd').textContent !== '', null, { timeout: 10000 });
      const messages = {};
      for (const name of Object.keys(bad)) messages[name] = await errorOf(name);
      assert.match(messages.G, /enter a value/);
      assert.match(messages.f, /not a number/);
      assert.match(messages.mu, /contact\.mu must be >= 0/);
      assert.match(messages.cd, /roller\.cd must be/);
      assert.match(await page.textContent('#status'), /invalid input \(4 fields\)/);
      for (const [name, text] of Object.entries(good)) await setInput(name, text);
      await settled();
      for (const name of Object.keys(bad)) assert.equal(await errorOf(name), '', name);
      console.log(`ok   four invalid inputs flagged at once: ${JSON.stringify(messages)}`);
    }

    // Pure rolling on the modulus soil (Appendix B): the exported TOML (soil.input = "modulus",
    // pure_rolling = true) is the case the native tool runs from the same flags.
    await page.selectOption('#soil_mode', 'modulus');
    await page.check('#rolling');
    shown = await settled();
    assert.equal(shown.status, 'steady_state');
    fs.writeFileSync(tomlFile, await page.evaluate(() => window.explorer.caseToml()));
    const modulusNative = native(['--set', 'soil.input=modulus', '--set', 'soil.G=40e6', '--pure-rolling']);
    assert.equal(native([tomlFile]).metrics.area, modulusNative.metrics.area);
    console.log(`ok   modulus soil, pure rolling: ${shown.status}, area ${shown.area}; TOML runs natively to the same case`);

    // The log-spiral trough at G = 5 (Table 2).
    await page.selectOption('#soil_mode', 'table2');
    await page.uncheck('#rolling');
    await page.selectOption('#trough_mode', 'spiral');
    await setInput('k', '0.002');
    await setInput('a', '0.601');
    await setInput('G', '5');
    shown = await settled();
    const spiral = native(['--k', '0.002', '--a', '0.601', '--G', '5', '--mu', '0.3']);
    assert.equal(shown.status, spiral.status);
    assert.ok(Math.abs(shown.area - spiral.metrics.area) <= AREA_RTOL * spiral.metrics.area, `spiral: area ${shown.area} vs native ${spiral.metrics.area}`);
    console.log(`ok   spiral trough k 0.002, a 0.601, G 5, mu 0.3: area ${shown.area} (native ${spiral.metrics.area})`);

    // M0 follows f^2 (5) when asked: M0 = M0(39 Hz) (f / 39)^2.
    await page.check('#M0_scale');
    await setInput('f', '30');
    await settled();
    const M0 = await page.evaluate(() => window.explorer.last().result.case['roller.M0']);
    assert.equal(M0, 54947 * (30 / 39) ** 2);
    await page.uncheck('#M0_scale');
    await setInput('f', '39');

    // A slow case (Dormand-Prince at rtol 1e-14: about 2 s here) keeps the engine busy: the page
    // stays responsive meanwhile, and a change after a second abandons it (the worker is
    // restarted) and shows the new case.
    await page.click('summary');
    await setInput('x:numerics.atol', '1e-17');
    await setInput('x:numerics.rtol', '1e-14');
    let sawBusy = false;
    for (let k = 0; k < 10; k++) {
      const t1 = Date.now();
      sawBusy = (await page.evaluate(() => window.explorer.busy())) || sawBusy;
      assert.ok(Date.now() - t1 < 500, 'the page froze during a long case');
      await page.waitForTimeout(110);
    }
    await setInput('x:numerics.rtol', '1e-8');
    await setInput('x:numerics.atol', '1e-11');
    shown = await settled();
    assert.equal(shown.status, spiral.status);
    assert.ok(Math.abs(shown.area - spiral.metrics.area) <= AREA_RTOL * spiral.metrics.area);
    await page.click('summary');
    console.log(`ok   the page stayed responsive ${sawBusy ? 'while the engine was busy with a slow case' : '(the slow case finished within a second)'}; the next change shows the new case`);

    // Back to the default case (for the screenshot).
    await page.selectOption('#trough_mode', 'circle');
    await setInput('G', '25');
    await setInput('mu', '0.5');
    shown = await settled();
    console.log(`ok   ${await page.textContent('#timing')}`);
    assert.ok(Math.abs(shown.area - def.metrics.area) <= AREA_RTOL * def.metrics.area);

    // The roller selector at the top (issue 28, point 4). The vibratory drum starts as
    // examples/vibratory.toml (0.9 kg m at 30 Hz, circular exciter, contact that can open) on the
    // page's soil and trough (here the defaults, the file's): the page runs that file's case, key
    // by key, and shows the native engine's numbers for it; the oscillation drum's inputs and rows
    // are gone and the vibratory drum's are there; a link, and a query with only roller.type,
    // restore it; bad static moments are named with their rule; switching back restores the
    // oscillation drum's default case.
    {
      const metricRow = (name) => page.evaluate((n) => { const tr = [...document.querySelectorAll('#metrics tbody tr')].find((t) => t.dataset.metric === n); return tr ? tr.textContent : ''; }, name);
      const rowNames = () => page.evaluate(() => [...document.querySelectorAll('#metrics tbody tr')].map((tr) => tr.dataset.metric));
      const visible = (name) => page.isVisible(`[id="in-${name}"]`);
      const OSCILLATION_ONLY = { inputs: ['M0', 'MMd', 'x:roller.unbalance'], rows: ['lag of φ behind the torque', "lag x_M''→z_M'' ψ", 'M0, MMd'] };
      const VIBRATORY_ONLY = { inputs: ['static_moment', 'exciter', 'torque'], rows: ['operating mode', 'kb', 'CMV-type, RMV-type', 'm_u e_u, F0, exciter'] };
      const checkRoller = async (own, other) => {
        await page.click('summary');  // 'more parameters' open: its roller keys are shown or hidden too
        for (const name of own.inputs) assert.ok(await visible(name), `input ${name} is not shown`);
        for (const name of other.inputs) assert.ok(!(await visible(name)), `input ${name} of the other roller is shown`);
        await page.click('summary');
        const rows = await rowNames();
        for (const name of own.rows) assert.ok(rows.includes(name), `row '${name}' missing: ${rows}`);
        for (const name of other.rows) assert.ok(!rows.includes(name), `row '${name}' of the other roller: ${rows}`);
      };
      await checkRoller(OSCILLATION_ONLY, VIBRATORY_ONLY);
      assert.ok(await page.isVisible('#M0_scale'));
      assert.match(await page.textContent('h1'), /oscillation drum/);

      await page.selectOption('#roller_type', 'vibratory');
      await page.waitForFunction(() => location.search.includes('roller.type=vibratory'));
      shown = await settled();
      const vibFile = path.resolve(__dirname, '../../examples/vibratory.toml');
      const vib = native([vibFile]);
      // The case the page ran is the file's, key by key (choices by name, booleans as 0/1).
      const ran = await page.evaluate(() => window.explorer.last().result.case);
      const pageFields = await page.evaluate(() => window.explorer.fields());
      for (const f of pageFields) {
        const want = vib.parameters[f.key];
        const got = f.type === 'choice' ? f.choices[ran[f.key]] : f.type === 'boolean' ? ran[f.key] === 1 : ran[f.key];
        assert.ok(got === want || (f.type === 'real' && Math.abs(got - want) <= 1e-15 * Math.abs(want)), `${f.key}: page ${got}, examples/vibratory.toml ${want}`);
      }
      assert.equal(shown.status, vib.status);
      const m = await page.evaluate(() => window.explorer.last().result.metrics);
      for (const key of ['area', 'kb', 'cmv', 'flight_fraction', 'ddz_max', 'ddx_max', 'liftoffs_per_period']) {
        assert.ok(Math.abs(m[key] - vib.metrics[key]) <= AREA_RTOL * Math.abs(vib.metrics[key]), `vibratory ${key}: page ${m[key]}, native ${vib.metrics[key]}`);
      }
      assert.ok(vib.metrics.flight_fraction > 0.1, `the example should lift off: ${vib.metrics.flight_fraction}`);
      // What the table shows: the native operating mode, kb in MN/m and the flight share.
      const mode = vib.diagnostics.operating_mode;
      assert.equal(mode, 'partial uplift');
      assert.match(await metricRow('operating mode'), new RegExp(mode));
      assert.ok((await metricRow('kb')).includes(String(Number((vib.metrics.kb / 1e6).toPrecision(5)))), await metricRow('kb'));
      assert.ok((await metricRow('stick / slip+ / slip− / flight')).includes(`${Number((100 * vib.metrics.flight_fraction).toPrecision(3))} %`), await metricRow('stick / slip'));
      // max |T| / N is unbounded where N falls to 0 at a lift-off: no number is shown for it
      assert.match(await metricRow('required μ'), /n\/a/);
      await checkRoller(VIBRATORY_ONLY, OSCILLATION_ONLY);
      assert.match(await page.textContent('h1'), /vibratory drum/);
      assert.doesNotMatch(await page.textContent('h1'), /oscillation/);
      assert.match(await page.title(), /vibratory drum/);
      assert.ok(await page.isVisible('#flight-key'));
      assert.ok(!(await page.isVisible('#M0_scale')));
      // Its exported case file runs natively to the same case.
      fs.writeFileSync(tomlFile, await page.evaluate(() => window.explorer.caseToml()));
      assert.match(fs.readFileSync(tomlFile, 'utf8'), /type = "vibratory"/);
      assert.equal(native([tomlFile]).metrics.area, vib.metrics.area);
      console.log(`ok   roller selector: vibratory drum ${shown.status}, ${mode}, area ${shown.area}, kb ${(m.kb / 1e6).toFixed(2)} MN/m, flight ${vib.metrics.flight_fraction.toFixed(3)} (native examples/vibratory.toml: the same); no M0, MMd, phi lag; its TOML runs natively to the same area`);

      // The exciter is the vibratory drum's own input: turning the other way mirrors x_M''.
      await page.selectOption('[id="in-exciter"]', { label: 'circular_reversed' });
      await page.waitForFunction(() => location.search.includes('roller.exciter=circular_reversed'));
      shown = await settled();
      const reversed = native([vibFile, '--set', 'roller.exciter=circular_reversed']);
      const mr = await page.evaluate(() => window.explorer.last().result.metrics);
      for (const key of ['area', 'ddx_max', 'ddx_min']) {
        assert.ok(Math.abs(mr[key] - reversed.metrics[key]) <= AREA_RTOL * Math.abs(reversed.metrics[key]), `reversed exciter ${key}: page ${mr[key]}, native ${reversed.metrics[key]}`);
      }
      assert.ok(Math.abs(reversed.metrics.ddx_max - vib.metrics.ddx_max) > 1e-2 * vib.metrics.ddx_max, 'the exciter changed nothing');
      console.log(`ok   circular_reversed exciter: x_M'' max ${mr.ddx_max} (native ${reversed.metrics.ddx_max}; circular ${vib.metrics.ddx_max})`);

      // A link restores the vibratory drum; so does a query naming only the roller (its defaults).
      for (const [query, want] of [[new URL(page.url()).search, reversed], ['?roller.type=vibratory', vib]]) {
        const p2 = await browser.newPage();
        p2.on('pageerror', (e) => consoleErrors.push(String(e.stack || e)));
        await p2.goto(url + query);
        await p2.waitForFunction(() => window.explorer && !window.explorer.busy() && window.explorer.last(), null, { timeout: 30000 });
        assert.equal(await p2.inputValue('#roller_type'), 'vibratory', query);
        const area = Number(await p2.getAttribute('#area-caption', 'data-value'));
        assert.ok(Math.abs(area - want.metrics.area) <= AREA_RTOL * want.metrics.area, `${query}: area ${area} vs native ${want.metrics.area}`);
        const ddx = await p2.evaluate(() => window.explorer.last().result.metrics.ddx_max);
        assert.ok(Math.abs(ddx - want.metrics.ddx_max) <= AREA_RTOL * want.metrics.ddx_max, `${query}: x_M'' max ${ddx} vs native ${want.metrics.ddx_max}`);
        assert.ok(!(await p2.isVisible('#in-M0')), query);
        await p2.close();
        console.log(`ok   ${query.slice(0, 60)}...: the vibratory drum, area ${area}`);
      }
      // The directed vertical exciter: x_M'' is round-off (1e-22 m/s^2). The page draws it flat on
      // zero on the scale of z_M'' and says it is absent (the time plot's legend, the figure's
      // scale and caption, no spectrum bars, the table), instead of scaling the round-off up.
      await page.selectOption('[id="in-exciter"]', { label: 'vertical' });
      await page.waitForFunction(() => location.search.includes('roller.exciter=vertical'));
      shown = await settled();
      {
        const got = await page.evaluate(() => {
          const r = window.explorer.last().result;
          const note = document.querySelector('#plot-spec-x .absent-note');
          const zNote = document.querySelector('#plot-spec-z .absent-note');
          return {
            status: r.status, absent: r.absent, scales: window.explorer.timeScales(),
            legend: Array.from(document.querySelectorAll('#plot-time .u-legend .u-label'), (e) => e.textContent),
            bars: window.explorer.spectrum('plot-spec-x'), zBars: window.explorer.spectrum('plot-spec-z'),
            note: note && !note.hidden ? note.textContent : '', zNote: zNote && !zNote.hidden ? zNote.textContent : '',
            caption: document.getElementById('area-caption').textContent,
            table: document.getElementById('metrics').textContent,
          };
        });
        assert.equal(got.status, 'steady_state');
        assert.deepEqual(got.absent, { ddx_M: true, ddz_M: false });
        const vert = native([vibFile, '--set', 'roller.exciter=vertical']);
        assert.ok(Math.abs(vert.metrics.ddx_max) < 1e-6 * vert.metrics.ddz_max, `native x_M'' max ${vert.metrics.ddx_max}`);
        assert.ok(got.scales.ax[1] >= vert.metrics.ddz_max && got.scales.ax[0] <= -vert.metrics.ddz_max, `x_M'' axis ${got.scales.ax}: not on the scale of z_M''`);
        assert.ok(got.legend.some((l) => /x_M'' \(absent: round-off only\)/.test(l)), JSON.stringify(got.legend));
        assert.ok(got.bars.every((v) => v === 0) && got.zBars.some((v) => v > 1), JSON.stringify(got.bars));
        assert.match(got.note, /x_M'' absent: round-off only/);
        assert.equal(got.zNote, '');
        assert.match(got.caption, /^0 \(x_M'' absent: round-off/);
        assert.match(got.table, /absent: round-off only/);
        console.log(`ok   vertical exciter: x_M'' absent (native max ${vert.metrics.ddx_max.toExponential(2)} m/s^2), drawn flat on the scale of z_M'' [${got.scales.ax.map((v) => v.toFixed(1))}], no x bars, "${got.caption}"`);
      }
      await page.selectOption('[id="in-exciter"]', { label: 'circular' });
      await settled();

      // Bad static moments: a message next to the input naming the key and its rule.
      for (const [text, pattern] of [
        ['-0.5', /roller\.static_moment must be >= 0 \[kg m\]; got -0\.5/],
        ['0', /roller\.static_moment must be > 0 \[kg m\] with roller\.type = vibratory/],
        ['', /enter a value: roller\.static_moment \(rule: >= 0 kg m\)/],
        ['heavy', /not a number: 'heavy'; roller\.static_moment \(rule: >= 0 kg m\)/],
      ]) {
        await setInput('static_moment', text);
        await page.waitForFunction(() => document.getElementById('err-static_moment').textContent !== '', null, { timeout: 10000 });
        const msg = await errorOf('static_moment');
        assert.match(msg, pattern, `static moment '${text}'`);
        assert.equal(await page.evaluate(() => document.getElementById('status').className), 'bad');
        console.log(`ok   static moment '${text}': "${msg}"`);
      }
      await setInput('static_moment', '0.9');
      await page.waitForFunction(() => document.getElementById('err-static_moment').textContent === '');
      shown = await settled();
      assert.ok(Math.abs(shown.area - vib.metrics.area) <= AREA_RTOL * vib.metrics.area);

      // Back to the oscillation drum: its default case, inputs and rows.
      await page.selectOption('#roller_type', 'oscillation');
      await page.waitForFunction(() => location.search.includes('roller.type=oscillation'));
      shown = await settled();
      assert.equal(shown.status, def.status);
      assert.ok(Math.abs(shown.area - def.metrics.area) <= AREA_RTOL * def.metrics.area, `back to the oscillation drum: area ${shown.area} vs native default ${def.metrics.area}`);
      assert.equal(await page.inputValue('#in-f'), '39');
      assert.equal(await page.isChecked('[id="in-x:contact.unilateral"]'), false);
      await checkRoller(OSCILLATION_ONLY, VIBRATORY_ONLY);
      assert.match(await page.textContent('h1'), /oscillation drum/);
      assert.ok(!(await page.isVisible('#flight-key')));
      console.log(`ok   back to the oscillation drum: the default case (area ${shown.area}, native ${def.metrics.area})`);
    }

    if (screenshot) {
      await page.waitForTimeout(700);  // a frame of the animation
      await page.screenshot({ path: screenshot, fullPage: true });
      console.log(`ok   screenshot ${screenshot}`);
    }
    assert.deepEqual(foreign, [], 'requests to other hosts');
    assert.deepEqual(consoleErrors, [], 'console errors');
    console.log('ok   no console error');
  } finally {
    if (browser) await browser.close();
    server.kill();
    fs.rmSync(profile, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
