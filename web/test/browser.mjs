// What the browser tests share: Debian's chromium, headless, with WebGL2 on
// SwiftShader; and a canvas's pixels.
import puppeteer from "puppeteer-core";

export function launch() {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
}

/// The RGBA bytes of the canvas SELECTOR, rows top first, read through a 2D
/// canvas (a WebGL2 canvas made with preserveDrawingBuffer, as the page's).
export function canvasPixels(page, selector = "canvas") {
  return page.$eval(selector, (c) => {
    const t = document.createElement("canvas");
    t.width = c.width;
    t.height = c.height;
    const x = t.getContext("2d");
    x.drawImage(c, 0, 0);
    return Array.from(x.getImageData(0, 0, c.width, c.height).data);
  });
}
