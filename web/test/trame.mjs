// PyVista's trame backend with server-side rendering, in Debian's headless
// chromium: the page of a real trame server whose one view is a plotter with
// the flow texture (python/package_tests/test_trame.py starts it).
//   node web/test/trame.mjs URL WIDTHxHEIGHT OUT-A.png OUT-B.png
// Waits until the view shows a picture (the server's render, sent as an
// image), saves it, waits a second and a half and saves the next; prints
// {"waited_ms"}. Exit 1 with what the console said when no picture came.
import { launch } from "./browser.mjs";

const [url, size, first, second] = process.argv.slice(2);
if (!url || !size || !first || !second) {
  console.error("usage: node web/test/trame.mjs URL WIDTHxHEIGHT OUT-A.png OUT-B.png");
  process.exit(2);
}
const [width, height] = size.split("x").map(Number);
const browser = await launch();
let status = 0;
try {
  const page = await browser.newPage();
  const messages = [];
  page.on("pageerror", (e) => messages.push(e.message));
  page.on("console", (m) => { if (m.type() === "error") messages.push(m.text()); });
  await page.setViewport({ width, height });
  const start = Date.now();
  await page.goto(url, { waitUntil: "domcontentloaded", timeout: 120000 });
  // The remote view draws the server's pictures as images: wait for one that
  // is not blank (more than the background's colour in its middle row).
  const clip = { x: 0, y: 0, width, height };
  let shown = false;
  for (let i = 0; i < 240 && !shown; ++i) {
    await new Promise((r) => setTimeout(r, 500));
    try {
      shown = await page.evaluate(() => {
        const img = [...document.querySelectorAll("img")].find((e) => e.naturalWidth > 0 && e.src);
        return Boolean(img);
      });
    } catch (e) {
      messages.push(String(e.message));  // the page still loading (a frame replaced)
    }
  }
  if (!shown) throw new Error("the view showed no picture: " + messages.join(" | "));
  await new Promise((r) => setTimeout(r, 1500));
  await page.screenshot({ path: first, clip });
  await new Promise((r) => setTimeout(r, 1500));
  await page.screenshot({ path: second, clip });
  console.log(JSON.stringify({ waited_ms: Date.now() - start, messages }));
} catch (e) {
  console.error(String(e.stack || e));
  status = 1;
} finally {
  await browser.close();
}
process.exit(status);
