// The page around the renderer (docs/web.md): the canvas and its WebGL2
// context, the panel (play, the styles and their sliders, the time steps,
// saving a PNG, recording a WebM), the mouse, pen and touch, and the loop.
// The renderer and its camera are runtime.ts; Session::advance's order of a
// frame is PageRenderer.advance.
//
// The panel's settings are also reachable by name (PageControls): the
// notebook widget (widget.ts) sets them from Python and hears a person move
// them. The page's own script element start is main.ts.
//
// Sections: the page's elements; the context; the settings by name; the
// panel; recording; input; start.
import type { SceneHeader } from "./format";
import { Navigation, PageRenderer } from "./runtime";

// ---------------------------------------------------------------- the page's elements

export function say(root: HTMLElement, text: string): void {
  const p = document.createElement("p");
  p.className = "ibfvs-message";
  p.textContent = text;
  root.replaceChildren(p);
  console.warn("ibfvs: " + text);
}

// A slider; `log`: it moves on the logarithm of the value (spans like the
// step's, 0.25 to 64 pixels, where the common values are a few). With
// `controls` and `key`, the setting of that name.
function slider(panel: HTMLElement, label: string, min: number, max: number, value: number,
                change: (v: number) => void, log = false,
                controls?: PageControls, key?: string): HTMLInputElement {
  const wrap = document.createElement("label");
  wrap.textContent = label + " ";
  const input = document.createElement("input");
  const to = log ? Math.log : (v: number) => v, from = log ? Math.exp : (v: number) => v;
  input.type = "range";
  input.min = String(to(min));
  input.max = String(to(max));
  input.step = String((to(max) - to(min)) / 100);
  input.value = String(to(value));
  input.dataset.name = key ?? label;
  // The value as set: a range input holds only its steps' values.
  let current = value;
  input.addEventListener("input", () => {
    current = from(parseFloat(input.value));
    change(current);
    if (key) controls?.changed();
  });
  wrap.appendChild(input);
  panel.appendChild(wrap);
  if (controls && key)
    controls.add(key, {
      get: () => current,
      set: (v) => {
        if (typeof v !== "number" || !Number.isFinite(v)) return false;
        current = Math.min(Math.max(v, min), max);
        input.value = String(to(current));
        change(current);
        return true;
      },
    });
  return input;
}

// ---------------------------------------------------------------- the settings by name

/// A setting's value: a slider's number, a checkbox's or play's on, the style's name.
export type SettingValue = number | boolean | string;

interface Control {
  get(): SettingValue;
  set(value: SettingValue): boolean; // false: not a value this control takes
}

/** The panel's settings by name: alpha, beta, step (pixels a frame) or
 * speed, scale (the noise cells' pixels), style, playing, loop and hold,
 * as far as this page's scene and look have them. Setting one moves its
 * control as a person would; `onChange` hears the settings after a person
 * changed one (and after a new style brought its own sliders). */
export class PageControls {
  onChange: ((values: Record<string, SettingValue>) => void) | null = null;
  private readonly controls = new Map<string, Control>();

  add(name: string, control: Control): void {
    this.controls.set(name, control);
  }
  /** Drops the look's own settings (a new style brings its own). */
  remove(names: readonly string[]): void {
    for (const name of names) this.controls.delete(name);
  }
  /** Sets NAME as its control would; false where the page has no such
   * setting now or the value is not one it takes. */
  set(name: string, value: SettingValue): boolean {
    const control = this.controls.get(name);
    return control ? control.set(value) : false;
  }
  values(): Record<string, SettingValue> {
    const out: Record<string, SettingValue> = {};
    for (const [name, control] of this.controls) out[name] = control.get();
    return out;
  }
  changed(): void {
    this.onChange?.(this.values());
  }
}

// The look's own settings: each style brings its own.
const lookSettings = ["alpha", "beta", "step", "speed", "scale"] as const;

// What the panel, the input and the loop share.
interface PageState {
  playing: boolean;
  dtFactor: number; // the speed slider's factor on the look's dt
  time: number; // in time steps
  loop: boolean; // on from the last step to the first, else the last step holds
  hold: boolean; // each step shown as it is until the next, as ParaView shows steps
  timeSlider: HTMLInputElement | null;
  when: HTMLElement | null; // the shown step's date, where the data names its steps
  play: HTMLButtonElement;
}

// ---------------------------------------------------------------- the context

// The canvas and its renderer; null, with a message in the page, where
// this browser's WebGL2 cannot run it.
function openRenderer(root: HTMLElement, scene: SceneHeader, data: ArrayBuffer):
    { canvas: HTMLCanvasElement; renderer: PageRenderer } | null {
  const canvas = document.createElement("canvas");
  canvas.width = scene.width;
  canvas.height = scene.height;
  canvas.className = "ibfvs-canvas";
  // No alpha: F's alpha holds the statistics input, not coverage.
  const gl = canvas.getContext("webgl2", { alpha: false, antialias: false, preserveDrawingBuffer: true });
  if (!gl) {
    say(root, "This page needs WebGL2, which this browser does not offer (or has switched off): " +
              "the animated texture cannot be shown.");
    return null;
  }
  const missing = ["EXT_color_buffer_float", "OES_texture_float_linear", "EXT_float_blend"]
    .filter((name) => !gl.getExtension(name));
  if (missing.length) {
    say(root, "This page needs float render targets, which this browser's WebGL2 lacks (" +
              missing.join(", ") + "): the animated texture cannot be shown.");
    return null;
  }
  let renderer: PageRenderer;
  try {
    renderer = new PageRenderer(gl, scene, data);
  } catch (e) {
    say(root, "The page could not start its renderer: " + (e as Error).message);
    return null;
  }
  root.replaceChildren(canvas);
  return { canvas, renderer };
}

// ---------------------------------------------------------------- the panel

function addPanel(root: HTMLElement, canvas: HTMLCanvasElement, scene: SceneHeader,
                  renderer: PageRenderer, nav: Navigation, controls: PageControls): PageState {
  const panel = document.createElement("div");
  panel.className = "ibfvs-panel";
  root.appendChild(panel);
  const play = document.createElement("button");
  const state: PageState = { playing: true, dtFactor: 1, time: 0, loop: scene.loop, hold: false,
                             timeSlider: null, when: null, play };
  const setPlaying = (on: boolean) => {
    state.playing = on;
    play.textContent = on ? "Pause" : "Play";
  };
  setPlaying(true);
  play.addEventListener("click", () => {
    setPlaying(!state.playing);
    controls.changed();
  });
  controls.add("playing", {
    get: () => state.playing,
    set: (v) => typeof v === "boolean" && (setPlaying(v), true),
  });
  panel.appendChild(play);
  // A scene with a lock (the topology style) plays to it and stays: Replay starts it again.
  if (scene.lock) {
    const replay = document.createElement("button");
    replay.textContent = "Replay";
    replay.addEventListener("click", () => {
      renderer.reset();
      nav.moveTo(scene);
    });
    panel.appendChild(replay);
  }
  // The styles that take the page's data (the scene's own first): each
  // brings its own sliders.
  const sliders = document.createElement("span");
  sliders.style.display = "contents"; // its sliders flow in the panel
  const lookControls = () => {
    sliders.replaceChildren();
    controls.remove(lookSettings);
    state.dtFactor = 1;
    // The look's controls, as the library's rules say each acts (the header's
    // look.controls): the page decides none of them.
    for (const c of renderer.look.controls) {
      const uniform = c.acts === "uniform" ? renderer.look.uniforms.find((u) => u.name === c.uniform) : undefined;
      const act = c.acts === "dt" ? (v: number) => (state.dtFactor = v)
        : c.acts === "grid" ? (v: number) => renderer.setNoiseScale(v)
        : uniform ? (v: number) => { uniform.values[0] = v; renderer.applySettings([uniform]); }
        : undefined;
      // A uniform's slider starts where the look's uniform is (kept across looks).
      if (act) slider(sliders, c.label, c.min, c.max, uniform ? uniform.values[0] : c.value, act, c.log, controls, c.key);
    }
  };
  if (scene.looks.length > 1) {
    const wrap = document.createElement("label");
    wrap.textContent = "style ";
    const menu = document.createElement("select");
    menu.dataset.name = "style";
    scene.looks.forEach((look, i) => {
      const option = document.createElement("option");
      option.value = String(i);
      option.textContent = look.name;
      option.title = look.description;
      menu.appendChild(option);
    });
    const setLook = (index: number) => {
      menu.value = String(index);
      renderer.setLook(index);
      lookControls();
    };
    menu.addEventListener("change", () => {
      setLook(parseInt(menu.value, 10));
      controls.changed();
    });
    controls.add("style", {
      get: () => scene.looks[parseInt(menu.value, 10)].name,
      set: (v) => {
        const index = scene.looks.findIndex((look) => look.name === v);
        if (index < 0) return false;
        if (String(index) !== menu.value) setLook(index);
        return true;
      },
    });
    wrap.appendChild(menu);
    panel.appendChild(wrap);
  }
  lookControls();
  panel.appendChild(sliders);
  // Time steps: a slider over the steps, moving while playing; whether the
  // series loops, and whether each step holds (no blend towards the next).
  if (scene.steps > 1) {
    state.timeSlider = slider(panel, "time step", 0, scene.loop ? scene.steps : scene.steps - 1, 0, (v) => {
      state.time = v;
      renderer.setTime(shownTime(state));
      showStep(state, scene);
    });
    state.timeSlider.step = "0.01";
    // Beside it the step's time as the data states it (a netCDF field's dates).
    if (scene.step_labels.length === scene.steps) {
      state.when = document.createElement("span");
      state.when.dataset.name = "date";
      state.timeSlider.parentElement!.appendChild(state.when);
      showStep(state, scene);
    }
    checkbox(panel, "loop", state.loop, (on) => {
      state.loop = on;
      state.timeSlider!.max = String(on ? scene.steps : scene.steps - 1);
    }, controls, "loop");
    checkbox(panel, "hold each step", state.hold, (on) => {
      state.hold = on;
      renderer.setTime(shownTime(state));
    }, controls, "hold");
  }
  const save = document.createElement("button");
  save.textContent = "Save PNG";
  save.addEventListener("click", () => {
    const a = document.createElement("a");
    a.download = scene.name + ".png";
    a.href = canvas.toDataURL("image/png");
    a.click();
  });
  panel.appendChild(save);
  addRecorder(panel, canvas, scene.name);
  return state;
}

// A labelled checkbox in the panel; the setting KEY of `controls`.
function checkbox(panel: HTMLElement, label: string, on: boolean, change: (on: boolean) => void,
                  controls: PageControls, key: string): HTMLInputElement {
  const row = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox";
  box.checked = on;
  box.dataset.name = label;
  box.addEventListener("change", () => {
    change(box.checked);
    controls.changed();
  });
  controls.add(key, {
    get: () => box.checked,
    set: (v) => {
      if (typeof v !== "boolean") return false;
      box.checked = v;
      change(v);
      return true;
    },
  });
  row.appendChild(box);
  row.appendChild(document.createTextNode(" " + label));
  panel.appendChild(row);
  return box;
}

// The slider's date: that of the step the time is at or past (as the
// viewer's panel names it).
function showStep(state: PageState, scene: SceneHeader): void {
  if (!state.when) return;
  const text = " " + scene.step_labels[Math.floor(state.time) % scene.steps];
  if (state.when.textContent !== text) state.when.textContent = text;  // not each frame anew
}

// The time the renderer shows: the playing time, or its step where steps hold.
function shownTime(state: PageState): number {
  return state.hold ? Math.floor(state.time) : state.time;
}

// The time a frame later (Session::seek's session_time): on from the first
// step where the series loops, else held at the last.
function nextTime(state: PageState, scene: SceneHeader): number {
  const t = state.time + 1 / scene.frames_per_step;
  return state.loop ? t % scene.steps : Math.min(t, scene.steps - 1);
}

// ---------------------------------------------------------------- recording

// A WebM of the canvas while recording (MediaRecorder), saved on stop.
function addRecorder(panel: HTMLElement, canvas: HTMLCanvasElement, name: string): void {
  if (typeof MediaRecorder !== "undefined" && "captureStream" in canvas) {
    const record = document.createElement("button");
    record.textContent = "Record WebM";
    let recorder: MediaRecorder | null = null;
    record.addEventListener("click", () => {
      if (recorder) {
        recorder.stop();
        return;
      }
      const chunks: Blob[] = [];
      recorder = new MediaRecorder(canvas.captureStream(30), { mimeType: "video/webm" });
      recorder.ondataavailable = (e) => chunks.push(e.data);
      recorder.onstop = () => {
        const blob = new Blob(chunks, { type: "video/webm" });
        (window as unknown as { ibfvsRecording: number }).ibfvsRecording = blob.size;
        const a = document.createElement("a");
        a.download = name + ".webm";
        a.href = URL.createObjectURL(blob);
        a.click();
        recorder = null;
        record.textContent = "Record WebM";
      };
      recorder.start(250);
      record.textContent = "Stop recording";
    });
    panel.appendChild(record);
  }
}

// ---------------------------------------------------------------- input

function attachInput(canvas: HTMLCanvasElement, scene: SceneHeader, nav: Navigation,
                     state: PageState, keys: HTMLElement | Document): void {
  // Mouse, pen and touch: one pointer turns (or pans with shift), two pinch to zoom.
  let last: [number, number] | null = null;
  const pointers = new Map<number, [number, number]>();
  const spread = () => {
    const [a, b] = [...pointers.values()];
    return Math.hypot(a[0] - b[0], a[1] - b[1]);
  };
  canvas.addEventListener("pointerdown", (e) => {
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    last = [e.clientX, e.clientY];
    canvas.setPointerCapture(e.pointerId);
  });
  const lift = (e: PointerEvent) => {
    pointers.delete(e.pointerId);
    last = null;
  };
  canvas.addEventListener("pointercancel", lift);
  canvas.addEventListener("pointermove", (e) => {
    if (pointers.size === 2 && pointers.has(e.pointerId)) {
      const before = spread();
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
      if (before > 0) nav.zoom = Math.min(Math.max((nav.zoom * spread()) / before, 0.1), 20);
      return;
    }
    if (pointers.has(e.pointerId)) pointers.set(e.pointerId, [e.clientX, e.clientY]);
    if (!last) return;
    if (e.shiftKey) {
      nav.pan[0] += (2 * (e.clientX - last[0])) / scene.width;
      nav.pan[1] -= (2 * (e.clientY - last[1])) / scene.height;
    } else {
      nav.drag(e.clientX - last[0], e.clientY - last[1]);
    }
    last = [e.clientX, e.clientY];
  });
  canvas.addEventListener("pointerup", lift);
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    nav.zoom = Math.min(Math.max(nav.zoom * Math.exp(-e.deltaY * 0.001), 0.1), 20);
  }, { passive: false });
  keys.addEventListener("keydown", (e) => {
    if ((e as KeyboardEvent).key !== " ") return;
    e.preventDefault();
    state.play.click();
  });
}

// ---------------------------------------------------------------- start

/// A running page: its renderer, its settings by name, and stop (the loop
/// ends and the context is given back: a notebook's widget removed).
export interface RunningPage {
  renderer: PageRenderer;
  controls: PageControls;
  stop(): void;
}

/** Starts the page in ROOT. `keys`: where the space bar pauses (the whole
 * document for a page of its own; a widget its own element, so typing in
 * a notebook does not pause it). */
export function start(root: HTMLElement, scene: SceneHeader, data: ArrayBuffer,
                      keys: HTMLElement | Document = document): RunningPage | null {
  const opened = openRenderer(root, scene, data);
  if (!opened) return null;
  const { canvas, renderer } = opened;
  const nav = new Navigation(scene);
  const controls = new PageControls();
  const state = addPanel(root, canvas, scene, renderer, nav, controls);
  attachInput(canvas, scene, nav, state, keys);
  let running = true;
  const tick = () => {
    if (!running) return;
    if (state.playing) {
      // Frame k at time k / frames_per_step, as Session::advance.
      if (scene.steps > 1) {
        renderer.setTime(shownTime(state));
        if (state.timeSlider) state.timeSlider.value = String(state.time);
        showStep(state, scene);
      }
      renderer.advance(nav, state.dtFactor);
    }
    renderer.present();
    const w = window as unknown as { ibfvsFrames: number; ibfvsTime: number; ibfvsLocked: boolean };
    w.ibfvsFrames = renderer.frame;
    w.ibfvsLocked = renderer.locked;
    w.ibfvsTime = state.time;
    if (state.playing && scene.steps > 1) state.time = nextTime(state, scene);
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  return {
    renderer,
    controls,
    stop: () => {
      running = false;
      canvas.getContext("webgl2")?.getExtension("WEBGL_lose_context")?.loseContext();
    },
  };
}
