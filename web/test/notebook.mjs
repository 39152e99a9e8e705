// The notebook widget in a real JupyterLab, in Debian's headless chromium
// (WebGL2 on SwiftShader), driven by puppeteer-core. Run by
// python/package_tests/test_notebook.py, which starts the server on a
// notebook whose one cell shows `ibfvs.widget(...)` and answers the page:
//   node web/test/notebook.mjs URL RESULT.json
// URL opens the notebook (with its token). It runs the cell, then:
//  1. the widget's canvas animates;
//  2. moving the page's beta slider reaches Python, whose observer sets
//     alpha from Python: the page's alpha slider moves, the animation going
//     on (no restart);
//  3. Pause and Play reach Python;
//  4. beta moved again: Python sets a background through set() (a key the
//     page cannot change live): the page starts again on the new scene.
// What it saw goes to RESULT.json; it exits non-zero on the first failure.
import fs from "node:fs";
import { canvasPixels, launch } from "./browser.mjs";

const [url, result] = process.argv.slice(2);
const seen = { steps: [] };
const note = (what) => {
  seen.steps.push(what);
  console.log("notebook test: " + what);
};
const browser = await launch();
const timeout = 240000;
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 1000 });
  const errors = [];
  page.on("pageerror", (e) => errors.push(`after "${seen.steps.at(-1)}": ${e.stack || e.message}`));
  page.on("console", (m) => {
    if (m.text().includes("ibfvs")) errors.push(m.text());
  });
  await page.goto(url, { waitUntil: "domcontentloaded", timeout });
  // The app (exposed by --LabApp.expose_app_in_browser), its notebook and
  // the notebook's kernel, idle.
  await page.waitForFunction(() => {
    const widget = window.jupyterapp?.shell?.currentWidget;
    return widget?.sessionContext?.session?.kernel?.status === "idle";
  }, { timeout, polling: 500 });
  note("kernel idle");
  await page.evaluate(() => window.jupyterapp.commands.execute("notebook:run-all-cells"));
  const root = ".ibfvs-widget";
  await page.waitForSelector(`${root} canvas`, { timeout });
  note("widget shown");

  // A hash of the canvas's pixels, its corner (the background) and the
  // share of pixels unlike the corner (the surface).
  const picture = async () => {
    const d = await canvasPixels(page, `${root} canvas`);
    let hash = 0, lit = 0;
    for (let i = 0; i < d.length; i += 4) {
      hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
      if (d[i] !== d[0] || d[i + 1] !== d[1]) ++lit;
    }
    return { hash, corner: [d[0], d[1], d[2]], lit: lit / (d.length / 4) };
  };
  const frames = () => page.evaluate(() => window.ibfvsFrames || 0);
  const waitFrames = (n) => page.waitForFunction((n) => (window.ibfvsFrames || 0) >= n, { timeout }, n);
  const slider = (name) => page.$eval(`${root} input[data-name="${name}"]`, (e) => parseFloat(e.value));
  const move = (name, value) => page.$eval(`${root} input[data-name="${name}"]`, (e, v) => {
    e.value = String(v);
    e.dispatchEvent(new Event("input", { bubbles: true }));
  }, value);

  // 1. It animates, and the surface covers part of the picture.
  await waitFrames(5);
  const first = await picture();
  await waitFrames((await frames()) + 5);
  const second = await picture();
  seen.animates = first.hash !== second.hash;
  seen.covered = second.lit;
  seen.corner_before = second.corner;
  note(`animates ${seen.animates}, surface covers ${(100 * second.lit).toFixed(0)}%`);

  // 2. Page to Python, and Python to the running page (the same canvas,
  // marked: no restart).
  await page.$eval(`${root} canvas`, (c) => (c.dataset.mark = "before"));
  const before = await frames();
  await move("beta", 0.2);
  await page.waitForFunction((root) => {
    const a = document.querySelector(`${root} input[data-name="alpha"]`);
    return a && Math.abs(parseFloat(a.value) - 0.37) < 0.006;
  }, { timeout }, root);
  seen.alpha_in_page = await slider("alpha");
  await waitFrames(before + 5);
  seen.frames_on = await page.$eval(`${root} canvas`, (c) => c.dataset.mark === "before");
  note(`alpha from Python ${seen.alpha_in_page}, frames going on ${seen.frames_on}`);

  // 3. Pause and play from the page.
  const play = await page.$(`${root} .ibfvs-panel button`);
  await play.click();
  const paused = await frames();
  await new Promise((r) => setTimeout(r, 1500));
  seen.pause_held = (await frames()) === paused;
  await play.click();
  note(`paused ${seen.pause_held}`);

  // 4. A key the page cannot change live: the page starts again, red.
  await move("beta", 0.5);
  for (const end = Date.now() + timeout; ;) {
    const { corner } = await picture();
    if (corner[0] > 200 && corner[1] < 60 && corner[2] < 60) break;
    if (Date.now() > end) throw new Error("the page did not start again on the red background");
    await new Promise((r) => setTimeout(r, 500));
  }
  await new Promise((r) => setTimeout(r, 1000));
  const red = await picture();
  seen.corner_after = red.corner;
  seen.alpha_after_restart = await slider("alpha");
  seen.beta_after_restart = await slider("beta");
  note(`new scene: corner ${red.corner}, alpha ${seen.alpha_after_restart}`);
  seen.errors = errors;
  fs.writeFileSync(result, JSON.stringify(seen, null, 1));
  await page.screenshot({ path: result.replace(/\.json$/, ".png") });
} catch (e) {
  seen.failure = String(e);
  fs.writeFileSync(result, JSON.stringify(seen, null, 1));
  console.error("notebook test: " + e);
  process.exitCode = 1;
} finally {
  await browser.close();
}
