// The page's own start (the bundle `ibfvs render --out NAME.html` embeds):
// the scene from the page's two script elements, once the mesh decoder's
// WebAssembly is ready.
import { MeshoptDecoder } from "meshoptimizer/decoder";
import { decodeBase64, type SceneHeader } from "./format";
import { say, start } from "./page";

const root = document.getElementById("ibfvs");
const header = document.getElementById("ibfvs-scene");
const block = document.getElementById("ibfvs-data");
if (root && header && block) {
  const scene = JSON.parse(header.textContent!) as SceneHeader;
  const data = decodeBase64(block.textContent!);
  MeshoptDecoder.ready.then(
    () => start(root, scene, data),
    (e: Error) => say(root, "This page needs WebAssembly to unpack its mesh: " + e.message));
}
