// A picture of a page's canvas, paused at a frame or a time, in headless
// chromium (SwiftShader WebGL2): what another program's test compares with
// its own picture (paraview/tests: the exported page against the view).
//   node web/test/shoot.mjs PAGE OUT.png [FRAMES] [TIME]
// waits until the page has drawn FRAMES frames (default 60) and its time
// reached TIME steps (default 0), pauses it (its Pause button), saves the
// canvas as OUT.png and prints {"frames", "time", "steps"} as JSON. Exit 1
// with what the console said on a page error or console error.
import path from "node:path";
import { launch } from "./browser.mjs";

const [file, shot, framesText = "60", timeText = "0"] = process.argv.slice(2);
if (!file || !shot) {
  console.error("usage: node web/test/shoot.mjs PAGE OUT.png [FRAMES] [TIME]");
  process.exit(2);
}
const frames = Number(framesText), time = Number(timeText);
const browser = await launch();
let status = 0;
try {
  const page = await browser.newPage();
  const messages = [];
  page.on("console", (m) => { if (m.type() === "error" || m.type() === "warn") messages.push(m.text()); });
  page.on("pageerror", (e) => messages.push(e.message));
  await page.goto("file://" + path.resolve(file));
  // Room for the whole canvas (chromium's window is 800x600; the page fits
  // a larger canvas to the window's width).
  const size = await page.evaluate(() => {
    const h = JSON.parse(document.getElementById("ibfvs-scene").textContent);
    return { width: h.width, height: h.height };
  });
  await page.setViewport({ width: Math.max(800, size.width + 64), height: Math.max(600, size.height + 240) });
  // Checked on every animation frame, paused in the same turn: the picture
  // is of the frame that met the condition, or the next.
  await page.waitForFunction(`(() => {
    if ((window.ibfvsFrames || 0) < ${frames} || (window.ibfvsTime || 0) < ${time}) return false;
    document.querySelector("button").click();
    return true;
  })()`, { timeout: 240000, polling: "raf" });
  await (await page.$("canvas")).screenshot({ path: shot });
  const state = await page.evaluate(() => ({
    frames: window.ibfvsFrames, time: window.ibfvsTime,
    steps: JSON.parse(document.getElementById("ibfvs-scene").textContent).steps,
  }));
  if (messages.length) {
    console.error(messages.join("\n"));
    status = 1;
  }
  console.log(JSON.stringify(state));
} finally {
  await browser.close();
}
process.exit(status);
