// The notebook widget (python/ibfvs/notebook.py, docs/python.md): the page's
// runtime as an anywidget module. The scene comes from the widget's model as
// the page's two parts (header: a JSON string; data: bytes); the settings
// are model fields of the same names as the page's (PageControls), kept
// equal both ways: a field set from Python moves the page's control, and a
// control a person moves sets the field.
import { MeshoptDecoder } from "meshoptimizer/decoder";
import type { SceneHeader } from "./format";
import { type RunningPage, type SettingValue, say, start } from "./page";

// The part of anywidget's model this uses.
interface Model {
  get(name: string): unknown;
  set(name: string, value: unknown): void;
  save_changes(): void;
  on(event: string, callback: () => void): void;
  off(event: string, callback: () => void): void;
}

/// The settings the model carries (python/ibfvs/notebook.py's traits), by
/// the page's names; the model's name for the style is "look" (ipywidgets
/// takes a widget's "style" for a style widget of its own).
const settings = ["alpha", "beta", "step", "speed", "scale", "style", "playing", "loop", "hold"];
const field = (name: string) => (name === "style" ? "look" : name);

// Bytes as they come from the model: a DataView of the comm's buffer (or an
// ArrayBuffer or typed array where a host passes it so).
function arrayBuffer(value: unknown): ArrayBuffer {
  if (value instanceof ArrayBuffer) return value;
  if (ArrayBuffer.isView(value))
    return value.buffer.slice(value.byteOffset, value.byteOffset + value.byteLength) as ArrayBuffer;
  throw new Error("the widget's data is not bytes");
}

function render({ model, el }: { model: Model; el: HTMLElement }): () => void {
  const root = document.createElement("div");
  root.className = "ibfvs-widget";
  root.tabIndex = 0; // the space bar pauses where the widget has the focus
  el.appendChild(root);
  let page: RunningPage | null = null;

  // The page's settings into the model, where they differ from it.
  const report = (values: Record<string, SettingValue>) => {
    let any = false;
    for (const [name, value] of Object.entries(values)) {
      if (model.get(field(name)) === value) continue;
      model.set(field(name), value);
      any = true;
    }
    if (any) model.save_changes();
  };
  // The model's settings into the page (those it has a value for), then
  // back: a value a control cannot take, or a style with its own sliders,
  // goes back to Python as the page holds it.
  const apply = (names: readonly string[]) => {
    if (!page) return;
    for (const name of names) {
      const value = model.get(field(name));
      if (value !== null && value !== undefined) page.controls.set(name, value as SettingValue);
    }
    report(page.controls.values());
  };
  const open = () => {
    page?.stop();
    page = null;
    try {
      const scene = JSON.parse(String(model.get("scene"))) as SceneHeader;
      page = start(root, scene, arrayBuffer(model.get("data")), root);
    } catch (e) {
      say(root, "The widget could not start its page: " + (e as Error).message);
    }
    if (!page) return;
    page.controls.onChange = report;
    // The style first: it brings the sliders the others move.
    apply(["style", ...settings.filter((name) => name !== "style")]);
  };
  const listeners = settings.map((name) => {
    const listener = () => apply([name]);
    model.on("change:" + field(name), listener);
    return ["change:" + field(name), listener] as const;
  });
  // A new scene (Python's set of a key the page cannot change live): the
  // page starts again on it.
  listeners.push(["change:scene", open]);
  model.on("change:scene", open);
  MeshoptDecoder.ready.then(open, (e: Error) =>
    say(root, "The widget needs WebAssembly to unpack its mesh: " + e.message));
  return () => {
    for (const [event, listener] of listeners) model.off(event, listener);
    page?.stop();
    page = null;
  };
}

export default { render };
