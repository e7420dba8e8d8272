// Opens geardyn's HTML plots in headless Chromium (Debian's, driven by playwright-core)
// in one browser session: no console error or page error, every plot rendered with the
// number of traces the page declares (and the SVG trace groups plotly drew), a
// screenshot of each page next to it (FILE.png, kept as a CI artefact).
//   node check_html.mjs FILE.html:PLOTS ...   (PLOTS: the plot elements expected)
import { chromium } from 'playwright-core';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  // no network here: keep Chromium from trying; software WebGL for the 3-D views
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
         '--disable-component-update', '--disable-sync', '--no-first-run',
         '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
let passed = 0, failed = 0;
const fail = (file, msg) => { failed++; console.log(`FAIL ${file}: ${msg}`); };
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 900 }, reducedMotion: 'reduce' });
  let errors = [];
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  // a self-contained page asks the network for nothing
  page.on('request', r => { if (!r.url().startsWith('file:') && !r.url().startsWith('blob:') &&
                                !r.url().startsWith('data:')) errors.push('request ' + r.url()); });
  for (const arg of process.argv.slice(2)) {
    const [name, want] = arg.split(':');
    const file = resolve(name);
    errors = [];
    const t0 = Date.now();
    // a shared 2-core machine at a load of 20 took over 30 s (the default) to load a report
    await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: 180000 });
    await page.waitForFunction(() => [...document.querySelectorAll('div.plot')]
      .every(d => d.classList.contains('js-plotly-plot') && d._fullLayout), null, { timeout: 180000 })
      .catch(() => errors.push('plots not drawn within 180 s'));
    const got = await page.evaluate(() => [...document.querySelectorAll('div.plot')].map(d => ({
      id: d.id, declared: +d.dataset.traces, data: (d.data || []).length,
      is3d: d.classList.contains('mode3d'),
      svgTraces: d.querySelectorAll('.scatterlayer .trace').length,
      gl: !!d.querySelector('canvas'),
    })));
    const csv = await page.evaluate(() => [...document.querySelectorAll('a.csv')]
      .filter(a => !a.href.startsWith('blob:')).length);
    let ok = errors.length === 0;
    if (errors.length) fail(file, 'console/page errors: ' + errors.slice(0, 5).join(' | '));
    if (got.length !== +want) { ok = false; fail(file, `${got.length} plots, expected ${want}`); }
    for (const g of got) {
      if (g.data !== g.declared) { ok = false; fail(file, `${g.id}: ${g.data} traces, page declares ${g.declared}`); }
      if (!g.is3d && g.svgTraces !== g.declared) { ok = false; fail(file, `${g.id}: ${g.svgTraces} drawn, expected ${g.declared}`); }
      if (g.is3d && !g.gl) { ok = false; fail(file, `${g.id}: no WebGL canvas for the 3-D view`); }
    }
    // 3-D views: each station's orbit passes through the deflected line at the phase
    // drawn (0: reduced motion stops the animation), at the station's axial position
    const orbits = await page.evaluate(() => [...document.querySelectorAll('div.mode3d')].map(d => {
      let n = 0, bad = [];
      for (const o of d.data.filter(t => t.name.endsWith(' orbits'))) {
        const l = d.data.find(t => t.name === o.name.slice(0, -7));
        if (!l) { bad.push(`${o.name}: no line`); continue; }
        for (let i = 0; i < l.x.length; i++, n++) {
          const k = 38 * i, tol = 1e-12;
          if (o.x[k] !== l.x[i] || Math.abs(o.y[k] - l.y[i]) > tol || Math.abs(o.z[k] - l.z[i]) > tol ||
              o.x[k + 37] !== null)
            bad.push(`${o.name} station ${i}`);
        }
      }
      return { id: d.id, n, bad };
    }));
    for (const o of orbits)
      if (o.bad.length || !o.n) { ok = false; fail(file, `${o.id}: orbits ${o.n} stations, off the line: ${o.bad.slice(0, 3).join(', ')}`); }
    if (csv) { ok = false; fail(file, `${csv} CSV links without their data`); }
    await page.screenshot({ path: file.replace(/\.html?$/, '.png'), fullPage: false });
    if (ok) { passed++; console.log(`ok ${file}: ${got.length} plots, ${got.reduce((a, g) => a + g.data, 0)} traces, ${orbits.reduce((a, o) => a + o.n, 0)} orbits, ${Date.now() - t0} ms`); }
  }
} finally {
  await browser.close();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
