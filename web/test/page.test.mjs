// The page in a real browser: Debian's chromium, headless, WebGL2 on
// SwiftShader, driven by puppeteer-core. Run by ctest (Web.page) with
// IBFVS (the ibfvs binary) and OUT (a scratch folder) set:
//   IBFVS=build/ibfvs OUT=/tmp/web node --test web/test/page.test.mjs
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import { canvasPixels, launch } from "./browser.mjs";
import Ajv from "ajv";

const ibfvs = process.env.IBFVS || "build/ibfvs";
const out = process.env.OUT || fs.mkdtempSync("/tmp/ibfvs-web-");
fs.mkdirSync(out, { recursive: true });
let browser;

before(async () => {
  browser = await launch();
});
after(async () => browser && (await browser.close()));

// A page of the cow in a flow turning about the view axis (the measure of
// `ibfvs quality --png` assumes that flow), written by ibfvs render.
function writePage(name, ...extra) {
  const file = path.join(out, name + ".html");
  execFileSync(ibfvs, ["render", "--mesh", "data/meshes/cow.off", "--field", "rotate:0,0,1",
                       "--size", "256x256", "--out", file, "-q", ...extra]);
  return file;
}

async function open(file, setup) {
  const page = await browser.newPage();
  const messages = [];
  page.on("console", (m) => { if (m.type() === "error" || m.type() === "warn") messages.push(m.text()); });
  page.on("pageerror", (e) => messages.push(e.message));
  if (setup) await page.evaluateOnNewDocument(setup);
  await page.goto("file://" + path.resolve(file));
  return { page, messages };
}

const frames = (page, n) => page.waitForFunction(`(window.ibfvsFrames || 0) >= ${n}`, { timeout: 120000 });
const frameNow = (page) => page.evaluate("window.ibfvsFrames");
// Pauses the page (its Pause button) once it has drawn n frames, checked on
// every animation frame: the picture of frame n or n + 1 stays.
const pauseAt = (page, n) => page.waitForFunction(`(() => {
  if ((window.ibfvsFrames || 0) < ${n}) return false;
  document.querySelector("button").click();
  return true;
})()`, { timeout: 120000, polling: "raf" });

async function shot(page, name) {
  const file = path.join(out, name + ".png");
  await (await page.$("canvas")).screenshot({ path: file });
  return file;
}

function alignment(png) {
  const text = execFileSync(ibfvs, ["quality", "--png", png], { encoding: "utf8" });
  return parseFloat(/alignment A\s+([0-9.]+)/.exec(text)[1]);
}

test("the page animates a texture aligned with the flow, without a console error", async () => {
  const { page, messages } = await open(writePage("cow"));
  await frames(page, 60);
  const first = fs.readFileSync(await shot(page, "cow-60"));
  const a = alignment(path.join(out, "cow-60.png"));
  const later = (await frameNow(page)) + 8;
  await frames(page, later);
  const second = fs.readFileSync(await shot(page, "cow-later"));
  // ibfvs render's frame of the same scene, as many frames in.
  const rendered = path.join(out, "cow-render.png");
  execFileSync(ibfvs, ["render", "--mesh", "data/meshes/cow.off", "--field", "rotate:0,0,1",
                       "--size", "256x256", "--frames", "61", "--out", rendered, "-q"]);
  const reference = alignment(rendered);
  assert.deepEqual(messages, []);
  // 0.5 is isotropic noise; both score about 0.935 here (docs/web.md).
  assert.ok(a > 0.85, `alignment ${a}`);
  assert.ok(Math.abs(a - reference) <= 0.03, `page ${a}, ibfvs render ${reference}`);
  assert.notDeepEqual(first, second, "two frames apart the picture must differ");
  await page.close();
});

// Which pixels show the surface (not the grey background): the texture
// changes every frame, the silhouette only when the mesh turns.
const silhouette = async (page) => {
  const d = await canvasPixels(page);
  const bits = [];
  for (let i = 0; i < d.length; i += 4)
    bits.push(d[i] === d[i + 1] && d[i + 1] === d[i + 2] && Math.abs(d[i] - 127.5) < 1 ? 0 : 1);
  return bits;
};
const changed = (a, b) => a.filter((v, i) => v !== b[i]).length / a.length;

test("a drag turns the mesh; the animation alone does not move it", async () => {
  const { page, messages } = await open(writePage("cow-drag"));
  await frames(page, 30);
  const start = await silhouette(page);
  await frames(page, (await frameNow(page)) + 5);
  const still = await silhouette(page);
  const box = await (await page.$("canvas")).boundingBox();
  await page.mouse.move(box.x + 128, box.y + 128);
  await page.mouse.down();
  await page.mouse.move(box.x + 200, box.y + 128, { steps: 5 });
  await page.mouse.up();
  await frames(page, (await frameNow(page)) + 5);
  const turned = await silhouette(page);
  await shot(page, "drag-after");
  assert.deepEqual(messages, []);
  assert.ok(changed(start, still) < 0.002, `still: ${changed(start, still)}`);
  assert.ok(changed(still, turned) > 0.03, `turned: ${changed(still, turned)}`);
  await page.close();
});

// Mean difference between horizontal neighbours on the surface: fine noise
// is rough, coarse noise smooth.
const roughness = async (page) => {
  const d = await canvasPixels(page);
  const grey = (i) => d[i] === d[i + 1] && d[i + 1] === d[i + 2] && Math.abs(d[i] - 127.5) < 1;
  let sum = 0, n = 0;
  for (let i = 0; i + 4 < d.length; i += 4)
    if (!grey(i) && !grey(i + 4)) { sum += Math.abs(d[i] - d[i + 4]); ++n; }
  return sum / n;
};
const differsFrom = (page, png) => page.evaluate(async (url) => {
  const image = new Image();
  image.src = url;
  await image.decode();
  const c = document.querySelector("canvas");
  const pixels = (source) => {
    const t = document.createElement("canvas");
    t.width = c.width;
    t.height = c.height;
    const x = t.getContext("2d");
    x.drawImage(source, 0, 0);
    return x.getImageData(0, 0, c.width, c.height).data;
  };
  const a = pixels(c), b = pixels(image);
  let differ = 0;
  for (let i = 0; i < a.length; i += 4)
    if (Math.max(...[0, 1, 2].map((k) => Math.abs(a[i + k] - b[i + k]))) > 24) ++differ;
  return differ / (a.length / 4);
}, "data:image/png;base64," + fs.readFileSync(png).toString("base64"));

test("the topology style: random cell colours, locked and seen obliquely, as ibfvs render", async () => {
  const args = ["render", "scenes/figure7-topology.toml", "--size", "128x128", "-q"];
  const file = path.join(out, "topology.html");
  const rendered = path.join(out, "topology.png");
  execFileSync(ibfvs, [...args, "--out", file]);
  execFileSync(ibfvs, [...args, "--out", rendered]);  // the lock frame + 60
  const { page, messages } = await open(file);
  await page.waitForFunction("window.ibfvsLocked === true", { timeout: 120000 });
  await frames(page, (await frameNow(page)) + 3);
  const before = await differsFrom(page, rendered);
  // The locked texture stays; turning the view still moves the mesh.
  const box = await (await page.$("canvas")).boundingBox();
  await page.mouse.move(box.x + 4, box.y + 64);
  await page.mouse.down();
  await page.mouse.move(box.x + 124, box.y + 64, { steps: 6 });  // 0.6 radians
  await page.mouse.up();
  await frames(page, (await frameNow(page)) + 3);
  const turned = await differsFrom(page, rendered);
  assert.deepEqual(messages, []);
  assert.ok(before < 0.01, `${before} of the pixels differ from ibfvs render's`);
  assert.ok(turned > 0.1, `turned, only ${turned} of the pixels differ`);
  await page.close();
});

// The page of a scene (128x128) against ibfvs render's frame 61 of it: under
// 3% of the pixels differ, and no console message.
async function assertMatchesRender(name, sceneArgs) {
  const args = ["render", ...sceneArgs, "--size", "128x128", "-q"];
  const file = path.join(out, name + ".html");
  const rendered = path.join(out, name + ".png");
  execFileSync(ibfvs, [...args, "--out", file]);
  execFileSync(ibfvs, [...args, "--frames", "61", "--out", rendered]);
  const { page, messages } = await open(file);
  await pauseAt(page, 61);
  const differ = await differsFrom(page, rendered);
  assert.deepEqual(messages, []);
  assert.ok(differ < 0.03, `${name}: ${differ} of the pixels differ from ibfvs render's`);
  await page.close();
}

test("a surface image colours the surface as in ibfvs render", async () => {
  // A colourful equirectangular image: the topology's cells, by ibfvs render.
  const image = path.join(out, "cells.png");
  execFileSync(ibfvs, ["render", "scenes/figure7-topology.toml", "--size", "96x48", "--out", image, "-q"]);
  await assertMatchesRender("globe", ["--mesh", "globe:4", "--surface-image", image,
                                      "--field", "rotate:0,1,0"]);
});

test("the scene's orbit turns the camera as in ibfvs render", async () => {
  // 120 degrees on at frame 61.
  await assertMatchesRender("orbit", ["--mesh", "data/meshes/cow.off", "--field", "rotate:0,0,1",
                                      "--orbit", "2"]);
});

test("the topology overlay draws over the page as over ibfvs render", async () => {
  // The height on a torus: two saddles (yellow), nodes, and separation
  // (red) and attachment (blue) lines, with the legend.
  const scene = ["--mesh", "torus", "--field", "gradient:down:1,0.5,0.137", "--overlay", "topology"];
  await assertMatchesRender("overlay", scene);
  const { page, messages } = await open(path.join(out, "overlay.html"));
  await pauseAt(page, 61);
  const rgba = await canvasPixels(page);
  const count = (r, g, b) => {
    let n = 0;
    for (let i = 0; i < rgba.length; i += 4)
      n += Math.abs(rgba[i] - r) < 30 && Math.abs(rgba[i + 1] - g) < 30 && Math.abs(rgba[i + 2] - b) < 30;
    return n;
  };
  assert.deepEqual(messages, []);
  assert.ok(count(220, 20, 30) > 20, "no separation line");
  assert.ok(count(30, 90, 255) > 20, "no attachment line");
  assert.ok(count(255, 221, 0) > 5, "no saddle");
  await page.close();
});

test("the page records a WebM of its canvas", async () => {
  const { page, messages } = await open(writePage("cow-record"));
  await frames(page, 5);
  const [record] = await page.$$("xpath/.//button[contains(., 'Record WebM')]");
  await record.click();
  await frames(page, (await frameNow(page)) + 10);
  await record.click();
  await page.waitForFunction("(window.ibfvsRecording || 0) > 1000", { timeout: 60000 });
  assert.deepEqual(messages, []);
  await page.close();
});

// A series of ASCII PLY files: a sphere (and its swirl about its own axis)
// turning `degrees` a step about +Y, its points moving; `rowsOf(k)`: step
// k's tessellation (rows of latitude; twice as many of longitude).
function writeTurningSeries(dir, steps, degrees, rowsOf = () => 24) {
  fs.mkdirSync(dir, { recursive: true });
  for (let k = 0; k < steps; ++k) {
    const rows = rowsOf(k), columns = 2 * rows;
    const base = [];
    for (let i = 0; i <= rows; ++i)
      for (let j = 0; j < columns; ++j) {
        const t = Math.PI * i / rows, f = 2 * Math.PI * j / columns;
        base.push([Math.sin(t) * Math.cos(f), Math.cos(t), Math.sin(t) * Math.sin(f)]);
      }
    const faces = [];
    for (let i = 0; i < rows; ++i)
      for (let j = 0; j < columns; ++j) {
        const a = i * columns + j, b = i * columns + (j + 1) % columns;
        faces.push([a, b, a + columns], [b, b + columns, a + columns]);
      }
    const angle = (degrees * k * Math.PI) / 180, c = Math.cos(angle), s = Math.sin(angle);
    const turn = ([x, y, z]) => [c * x + s * z, y, -s * x + c * z];
    const axis = turn([0.3, 1, 0]);
    const lines = base.map((p0) => {
      const p = turn(p0);
      const v = [axis[1] * p[2] - axis[2] * p[1], axis[2] * p[0] - axis[0] * p[2],
                 axis[0] * p[1] - axis[1] * p[0]];
      return [...p, ...v].map((x) => x.toFixed(6)).join(" ");
    });
    const text = ["ply", "format ascii 1.0", `element vertex ${base.length}`,
                  "property float x", "property float y", "property float z",
                  "property float vx", "property float vy", "property float vz",
                  `element face ${faces.length}`, "property list uchar int vertex_indices",
                  "end_header", ...lines, ...faces.map((f) => "3 " + f.join(" "))].join("\n");
    fs.writeFileSync(path.join(dir, `turn_${String(k).padStart(2, "0")}.ply`), text + "\n");
  }
  return path.join(dir, "turn_*.ply");
}

test("a series whose points move plays in the page as in ibfvs render", async () => {
  const series = writeTurningSeries(path.join(out, "turning"), 12, 10);
  const said = execFileSync(ibfvs, ["render", "--mesh", series, "--frames-per-step", "4",
                                    "--size", "128x128", "--out", path.join(out, "turning.html")],
                            { encoding: "utf8" });
  // Every vertex but the poles' moves; a set of their points per step.
  assert.match(said, /the surface moves: \d+ of its vertices, 12 sets of their points for 12 steps/);
  // Coloured by height along z, which changes as the sphere turns: each
  // step's colours, as the session sets them.
  await assertMatchesRender("turning", ["--mesh", series, "--frames-per-step", "4",
                                        "--color-by", "z"]);
});

test("a series' topology overlay moves between its steps in the page as in ibfvs render", async () => {
  // The swirl's two centres turn 10 degrees a step with the sphere; frame
  // 61 of 8 a step is 5/8 of the way from the last step into the first.
  const series = writeTurningSeries(path.join(out, "turning-topology"), 4, 10);
  await assertMatchesRender("turning-topology", ["--mesh", series, "--frames-per-step", "8",
                                                 "--overlay", "topology"]);
});

test("a series whose triangles change plays in the page as in ibfvs render", async () => {
  // Steps 2 and 3 are the sphere tessellated finer (meshes of their own):
  // the texture goes on from the image into them and back.
  const series = writeTurningSeries(path.join(out, "changing"), 6, 10, (k) => (k === 2 || k === 3 ? 30 : 24));
  const said = execFileSync(ibfvs, ["render", "--mesh", series, "--frames-per-step", "4",
                                    "--size", "128x128", "--out", path.join(out, "changing.html")],
                            { encoding: "utf8" });
  assert.match(said, /2 steps with triangles of their own/);
  await assertMatchesRender("changing", ["--mesh", series, "--frames-per-step", "4", "--color-by", "z"]);
});

test("the earth plays its months, with a time slider and their dates; the series ends at its last, or loops", async () => {
  const file = path.join(out, "earth.html");
  execFileSync(ibfvs, ["render", "scenes/figure6-earth-wind.toml", "--size", "128x128",
                       "--time", "0:2", "--frames-per-step", "4", "--out", file, "-q"]);
  const { page, messages } = await open(file);
  const slider = await page.waitForSelector('input[data-name="time step"]');
  assert.equal(await slider.evaluate((e) => e.max), "2");
  // The slider and the time read in one turn of the page's loop; the
  // series ends at its last step and holds it (no blend back to the first).
  await page.waitForFunction(() => {
    const time = window.ibfvsTime || 0;
    const shown = parseFloat(document.querySelector('input[data-name="time step"]').value);
    return time === 2 && Math.abs(shown - time) < 0.01;
  }, { timeout: 120000 });
  const frames = await page.evaluate(() => window.ibfvsFrames);
  await page.waitForFunction((k) => window.ibfvsFrames >= k + 8, { timeout: 60000 }, frames);
  assert.equal(await page.evaluate(() => window.ibfvsTime), 2);
  // Beside the slider, the step's date from the file's time axis: the
  // climatology's March (coads_climatology.cdf counts hours from year 0).
  assert.equal(await page.$eval('[data-name="date"]', (e) => e.textContent.trim()), "0000-03-17 02:58:12");
  // The loop toggle: the time goes back to the first step after the last.
  await page.click('input[data-name="loop"]');
  assert.equal(await slider.evaluate((e) => e.max), "3");
  await page.waitForFunction(() => window.ibfvsTime > 2.2, { timeout: 60000 });
  await page.waitForFunction(() => window.ibfvsTime < 1, { timeout: 60000 });
  assert.deepEqual(messages, []);
  await page.close();
});

test("without float render targets the page says so in words", async () => {
  const { page } = await open(writePage("cow-nofloat"), () => {
    const original = WebGL2RenderingContext.prototype.getExtension;
    WebGL2RenderingContext.prototype.getExtension = function (name) {
      return name === "EXT_color_buffer_float" ? null : original.call(this, name);
    };
  });
  await page.waitForSelector(".ibfvs-message");
  const text = await page.$eval("#ibfvs", (e) => e.textContent);
  assert.match(text, /float render targets/);
  assert.equal(await page.$("canvas"), null);
  await page.close();
});

test("a page needs a name ending in .html, and says so in one line", () => {
  assert.throws(() => execFileSync(ibfvs, ["render", "--mesh", "data/meshes/cow.off", "--out",
                                           path.join(out, "cow.htmlx")], { stdio: "pipe" }),
                (e) => e.status !== 0 && /unknown output type/.test(e.stderr.toString()));
});

// Every page written above (steady, styled, locked, moving, changing, the
// earth's months, ...) in the one format: the schema that the runtime's
// types are generated from (web/schema/page.schema.json).
test("every page written above matches the page schema", () => {
  const schema = JSON.parse(fs.readFileSync(new URL("../schema/page.schema.json", import.meta.url)));
  const validate = new Ajv({ allErrors: true, strict: true }).compile(schema);
  const pages = fs.readdirSync(out).filter((f) => f.endsWith(".html"));
  assert.ok(pages.length >= 10, `only ${pages.length} pages`);
  for (const name of pages) {
    const text = fs.readFileSync(path.join(out, name), "utf8");
    const header = text.match(/<script type="application\/json" id="ibfvs-scene">(.*?)<\/script>/s);
    assert.ok(header, name + ": no header");
    assert.ok(validate(JSON.parse(header[1])), name + ": " + JSON.stringify(validate.errors));
  }
  // And the schema holds: a header with a field it does not know fails.
  const some = JSON.parse(fs.readFileSync(path.join(out, pages[0]), "utf8")
    .match(/id="ibfvs-scene">(.*?)<\/script>/s)[1]);
  assert.ok(!validate({ ...some, unknown: 1 }));
  assert.ok(!validate({ ...some, looks: [{ ...some.looks[0], dt: "1" }] }));
});
