// Screenshots of geardyn's HTML plots for docs/figures (headless Chromium through
// playwright-core, as check_html.mjs): each argument FILE.html:OUT.png:K shoots the K-th
// plot of the page (K = top: the top of the page as it opens; K = ~TEXT: the first plot
// whose title holds TEXT), after every plot is drawn; FILE.html:OUT.png:K:M shows mode M
// (0-based) of a 3-D mode view first.
//   node figures.mjs FILE.html:OUT.png:K[:M] ...
import { chromium } from 'playwright-core';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
         '--disable-component-update', '--disable-sync', '--no-first-run',
         '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
let failed = 0;
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 760 }, reducedMotion: 'reduce' });
  let last = '';
  for (const arg of process.argv.slice(2)) {
    const [name, out, which, mode] = arg.split(':');
    const file = resolve(name);
    if (file !== last) {
      await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: 180000 });
      await page.waitForFunction(() => [...document.querySelectorAll('div.plot')]
        .every(d => d.classList.contains('js-plotly-plot') && d._fullLayout), null, { timeout: 180000 });
      last = file;
    }
    if (which === 'top') {
      await page.evaluate(() => window.scrollTo(0, 0));
      await page.screenshot({ path: resolve(out) });
    } else {
      let k = +which;
      if (which.startsWith('~'))
        k = await page.evaluate(t => [...document.querySelectorAll('div.plot')].findIndex(d =>
          d.layout && d.layout.title && String(d.layout.title.text || '').includes(t)), which.slice(1));
      if (!(k >= 0)) throw new Error(`${name}: no plot ${which}`);
      if (mode !== undefined) {
        const sel = await page.locator('div.plot').nth(k).evaluate(d => d.id + '-sel');
        await page.selectOption('#' + sel, mode);
        await page.waitForTimeout(500);
      }
      await page.locator('div.plot').nth(k).screenshot({ path: resolve(out) });
    }
    console.log(`${out}`);
  }
} catch (e) {
  failed = 1;
  console.log(String(e));
} finally {
  await browser.close();
}
process.exit(failed);
