// The runtime of an ibfvs page (docs/web.md). The page holds the prepared
// scene (a JSON header and one base64 block of binary arrays) and the GLSL
// ES 3.00 sources that ibfvs's one shader generator emitted for it; this
// script runs the same passes as the OpenGL renderer (src/render/
// ibfvs_renderer.cpp): the noise grid, the IBFVS pass into F_t and F, the
// contrast statistics, and shows F. Only what WebGL2 needs differently is
// here: sampler units set by name, extension checks, the canvas.
//
// Sections: the scene format; the page's elements; WebGL objects; the
// renderer; the camera and input; start.
import { mat4, vec3 } from "gl-matrix";
import { MeshoptDecoder } from "meshoptimizer/decoder";

// ---------------------------------------------------------------- the scene format

interface Uniform {
  name: string;
  type: "float" | "int" | "uint";
  values: number[];
  array?: boolean;
}

interface ArrayRef {
  offset: number; // bytes into the binary block
  length: number; // elements, or with a codec its encoded bytes
  codec?: "vertex" | "index"; // meshoptimizer's codecs (per-vertex arrays, triangle indices)
  stride?: number; // bytes a vertex (the vertex codec)
  elements?: number; // elements once decoded
}

/// An array of the block as `T` (Uint16Array, Float32Array, ...), decoded
/// where the page wrote it through a meshoptimizer codec.
function view<T>(data: ArrayBuffer, ref: ArrayRef,
                 make: (buffer: ArrayBuffer, offset: number, length: number) => T, bytesEach: number): T {
  if (!ref.codec) return make(data, ref.offset, ref.length);
  const source = new Uint8Array(data, ref.offset, ref.length);
  const target = new Uint8Array(ref.elements! * bytesEach);
  if (ref.codec === "vertex")
    MeshoptDecoder.decodeVertexBuffer(target, target.length / ref.stride!, ref.stride!, source);
  else MeshoptDecoder.decodeIndexBuffer(target, ref.elements!, 4, source);
  return make(target.buffer, 0, ref.elements!);
}
const u16 = (b: ArrayBuffer, o: number, n: number) => new Uint16Array(b, o, n);
const i8 = (b: ArrayBuffer, o: number, n: number) => new Int8Array(b, o, n);
const u32 = (b: ArrayBuffer, o: number, n: number) => new Uint32Array(b, o, n);
const f32 = (b: ArrayBuffer, o: number, n: number) => new Float32Array(b, o, n);

/// A camera of the page: its matrices (column-major 4x4) and look-at point.
interface Camera {
  view: number[];
  projection: number[];
  target: [number, number, number];
}

/// One style over the page's data: what the pass is compiled with and set to.
export interface Look {
  name: string;
  description: string;
  background: [number, number, number];
  dt: number;
  noise_rate: number;
  colour_texture: boolean;
  texture_channels: 2 | 4; // F_t: RG16F (grey value, depth) or RGBA16F (RGB or grey and displacement, depth)
  advect_previous: boolean;
  phase_size: [number, number]; // its noise grid: the first columns x rows of the page's phases
  shaders: { vertex: string; fragment: string; stats_fragment: string };
  uniforms: Uniform[];
  grid_uniforms: Uniform[];
}

export interface SceneHeader {
  format: "ibfvs-page";
  version: 2;
  name: string;
  width: number;
  height: number;
  no_depth: number;
  any_depth: number;
  // At this frame F_t stops and the camera moves to the lock view (null: never).
  lock: (Camera & { frame: number }) | null;
  orbit: { degrees: number; up: [number, number, number] } | null; // a frame, about the vertical
  target: [number, number, number]; // the look-at point
  probe: number;
  cull: number;
  stats: { size: number; every: number; weight: number };
  view: number[]; // column-major 4x4
  projection: number[];
  centre: [number, number, number];
  shaders: { grid_vertex: string; grid_fragment: string };
  looks: Look[]; // the scene's own first
  vertex_count: number;
  steps: number; // time steps of the field (1: steady)
  frames_per_step: number;
  index_count: number;
  phase_size: [number, number]; // of the phases array (the finest look's grid)
  arrays: {
    positions: ArrayRef & { min: number[]; max: number[] }; // uint16 x 4 (the last 0), in the box
    normals: ArrayRef; // int8 x 4 (snorm)
    vectors: ArrayRef; // float16 x 4, every time step one after the other
    scalars?: ArrayRef; // float32 x 2 (colour, beta)
    indices: ArrayRef; // uint32
    phases: ArrayRef; // uint16, phi * 65535
    color_map: ArrayRef; // uint8 RGBA x 256
    // The surface colour, an equirectangular image (uint8 RGBA, the bottom row first)
    surface_image?: ArrayRef & { width: number; height: number };
    // F_t's first colours, one per noise cell of `scale` pixels, float16 RGB_ by rows of `columns`
    cells?: ArrayRef & { columns: number; scale: number };
  };
}

/// An IEEE half float's value.
function halfToFloat(h: number): number {
  const exponent = (h >> 10) & 31, fraction = h & 1023, sign = h & 0x8000 ? -1 : 1;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

function decodeBase64(text: string): ArrayBuffer {
  const binary = atob(text.replace(/\s+/g, ""));
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

// ---------------------------------------------------------------- the page's elements

function say(root: HTMLElement, text: string): void {
  const p = document.createElement("p");
  p.className = "ibfvs-message";
  p.textContent = text;
  root.replaceChildren(p);
  console.warn("ibfvs: " + text);
}

function slider(panel: HTMLElement, label: string, min: number, max: number, value: number,
                change: (v: number) => void): HTMLInputElement {
  const wrap = document.createElement("label");
  wrap.textContent = label + " ";
  const input = document.createElement("input");
  input.type = "range";
  input.min = String(min);
  input.max = String(max);
  input.step = String((max - min) / 100);
  input.value = String(value);
  input.dataset.name = label;
  input.addEventListener("input", () => change(parseFloat(input.value)));
  wrap.appendChild(input);
  panel.appendChild(wrap);
  return input;
}

// ---------------------------------------------------------------- WebGL objects

function compile(gl: WebGL2RenderingContext, vertex: string, fragment: string): WebGLProgram {
  const program = gl.createProgram()!;
  for (const [type, source] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]] as const) {
    const shader = gl.createShader(type)!;
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
      throw new Error("shader: " + gl.getShaderInfoLog(shader));
    gl.attachShader(program, shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error("link: " + gl.getProgramInfoLog(program));
  // Sampler units: GLSL ES has no layout(binding); the sources keep the
  // generator's BINDING(n) marks, and the units are set from them by name.
  gl.useProgram(program);
  for (const source of [vertex, fragment])
    for (const m of source.matchAll(/BINDING\((\d+)\)\s+uniform\s+\w+\s+(\w+)/g))
      gl.uniform1i(gl.getUniformLocation(program, m[2]), parseInt(m[1], 10));
  return program;
}

// Uniform locations, looked up once per program and name (not every frame).
const locations = new WeakMap<WebGLProgram, Map<string, WebGLUniformLocation | null>>();
function locate(gl: WebGL2RenderingContext, program: WebGLProgram, name: string): WebGLUniformLocation | null {
  let known = locations.get(program);
  if (!known) locations.set(program, (known = new Map()));
  if (!known.has(name)) known.set(name, gl.getUniformLocation(program, name));
  return known.get(name)!;
}

function setUniform(gl: WebGL2RenderingContext, program: WebGLProgram, u: Uniform): void {
  const at = locate(gl, program, u.name);
  if (at === null) return; // compiled out
  const v = u.values;
  if (u.array) gl.uniform1fv(at, new Float32Array(v));
  else if (u.type === "uint") gl.uniform1ui(at, v[0]);
  else if (u.type === "int") v.length === 1 ? gl.uniform1i(at, v[0]) : gl.uniform2i(at, v[0], v[1]);
  else if (v.length === 1) gl.uniform1f(at, v[0]);
  else if (v.length === 2) gl.uniform2f(at, v[0], v[1]);
  else gl.uniform3f(at, v[0], v[1], v[2]);
}

function texture(gl: WebGL2RenderingContext, w: number, h: number, internal: number, format: number,
                 type: number, linear: boolean, data: ArrayBufferView | null = null): WebGLTexture {
  const t = gl.createTexture()!;
  gl.bindTexture(gl.TEXTURE_2D, t);
  gl.texImage2D(gl.TEXTURE_2D, 0, internal, w, h, 0, format, type, data);
  const filter = linear ? gl.LINEAR : gl.NEAREST;
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  return t;
}

function framebuffer(gl: WebGL2RenderingContext, colours: WebGLTexture[], depth: WebGLTexture | null): WebGLFramebuffer {
  const fb = gl.createFramebuffer()!;
  gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  colours.forEach((t, i) => gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, t, 0));
  if (depth) gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, depth, 0);
  gl.drawBuffers(colours.map((_, i) => gl.COLOR_ATTACHMENT0 + i));
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
    throw new Error("this browser cannot render into float textures (framebuffer incomplete)");
  return fb;
}

// ---------------------------------------------------------------- the renderer

export class PageRenderer {
  readonly gl: WebGL2RenderingContext;
  readonly scene: SceneHeader;
  look: Look;
  frame = 0;
  private main!: WebGLProgram;
  private grid: WebGLProgram;
  private stats!: WebGLProgram;
  private programs = new Map<Look, [WebGLProgram, WebGLProgram]>(); // compiled looks: main, stats
  private vao: WebGLVertexArrayObject;
  private empty: WebGLVertexArrayObject;
  private textures: WebGLTexture[] = [];
  private output: WebGLTexture;
  private depth: WebGLTexture;
  private fbs: WebGLFramebuffer[] = [];
  private gridTexture: WebGLTexture | null = null;
  private gridFb: WebGLFramebuffer | null = null;
  private allPhases: Float32Array;
  private phases: WebGLTexture | null = null;
  private phaseSize: [number, number] = [0, 0];
  private statsTexture: WebGLTexture;
  private statsFb: WebGLFramebuffer;
  private colorMap: WebGLTexture;
  private surfaceImage: WebGLTexture | null = null;
  private current = 0;
  private vectorBuffer: WebGLBuffer | null = null;
  private step = -1;
  private fieldMix = 0;
  private previousViewProjection: mat4 | null = null;
  private cells: Float32Array | null = null; // F_t's first texels (random cells), or null
  locked = false;
  private lockViewProjection: mat4 | null = null;

  constructor(gl: WebGL2RenderingContext, scene: SceneHeader, data: ArrayBuffer) {
    this.gl = gl;
    this.scene = scene;
    const s = scene, w = s.width, h = s.height;
    this.look = s.looks[0];
    this.grid = compile(gl, s.shaders.grid_vertex, s.shaders.grid_fragment);

    // The mesh: positions from 16 bits in the box, the rest as stored.
    const a = s.arrays;
    const q = view(data, a.positions, u16, 2);
    const positions = new Float32Array((q.length / 4) * 3);
    for (let i = 0; i < q.length; ++i) {
      const c = i % 4, lo = a.positions.min[c], hi = a.positions.max[c];
      if (c < 3) positions[(i >> 2) * 3 + c] = lo + (hi - lo) * (q[i] / 65535);
    }
    this.vao = gl.createVertexArray()!;
    gl.bindVertexArray(this.vao);
    const attribute = (location: number, bytes: ArrayBufferView, size: number, type: number, normalized: boolean) => {
      const b = gl.createBuffer()!;
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, bytes, gl.STATIC_DRAW);
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, size, type, normalized, 0, 0);
    };
    attribute(0, positions, 3, gl.FLOAT, false);
    attribute(1, view(data, a.normals, i8, 1), 4, gl.BYTE, true);
    // The field: attributes 2 and 4 read the current and the next time step
    // from one buffer (setTime moves them).
    this.vectorBuffer = gl.createBuffer()!;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vectorBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, view(data, a.vectors, u16, 2), gl.STATIC_DRAW);
    gl.enableVertexAttribArray(2);
    gl.enableVertexAttribArray(4);
    if (a.scalars) attribute(3, view(data, a.scalars, f32, 4), 2, gl.FLOAT, false);
    else gl.vertexAttrib2f(3, 0, 0);
    const indices = gl.createBuffer()!;
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indices);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, view(data, a.indices, u32, 4), gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    this.setTime(0);
    this.empty = gl.createVertexArray()!;

    // F and the depth; F_t, the grid and the programs come with the look.
    this.output = texture(gl, w, h, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, false);
    this.depth = texture(gl, w, h, gl.DEPTH_COMPONENT24, gl.DEPTH_COMPONENT, gl.UNSIGNED_INT, false);
    const p16 = new Uint16Array(data, a.phases.offset, a.phases.length);
    this.allPhases = new Float32Array(p16.length);
    for (let i = 0; i < p16.length; ++i) this.allPhases[i] = p16[i] / 65535;
    this.statsTexture = texture(gl, 1, 1, gl.RGBA32F, gl.RGBA, gl.FLOAT, false);
    this.statsFb = framebuffer(gl, [this.statsTexture], null);
    this.colorMap = texture(gl, 256, 1, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, true,
                            new Uint8Array(data, a.color_map.offset, a.color_map.length));
    if (a.surface_image) {
      const { width, height } = a.surface_image, largest = gl.getParameter(gl.MAX_TEXTURE_SIZE) as number;
      if (width > largest || height > largest)
        throw new Error(`its surface image of ${width}x${height} pixels is larger than this browser's ` +
                        `largest texture (${largest})`);
      this.surfaceImage = texture(gl, width, height, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, true,
                                  view(data, a.surface_image, (b, o, n) => new Uint8Array(b, o, n), 1));
    }
    if (a.cells) {
      // IbfvsRenderer::fill_texture_with_cell_colors: each texel its cell's colour, any depth.
      const c16 = new Uint16Array(data, a.cells.offset, a.cells.length);
      const { columns, scale } = a.cells;
      this.cells = new Float32Array(w * h * 4);
      for (let y = 0; y < h; ++y)
        for (let x = 0; x < w; ++x) {
          const cell = Math.floor(y / scale) * columns + Math.floor(x / scale), i = (y * w + x) * 4;
          for (let c = 0; c < 3; ++c) this.cells[i + c] = halfToFloat(c16[cell * 4 + c]);
          this.cells[i + 3] = s.any_depth;
        }
    }
    this.setLook(0);
  }

  /// Shows the scene in look `index` (a style over the same data), from a
  /// fresh texture: its programs (compiled once), F_t's channels, its noise
  /// grid and its uniforms.
  setLook(index: number): void {
    const gl = this.gl, s = this.scene, look = s.looks[index];
    const channels = this.textures.length ? this.look.texture_channels : 0;
    this.look = look;
    let programs = this.programs.get(look);
    if (!programs) {
      programs = [compile(gl, look.shaders.vertex, look.shaders.fragment),
                  compile(gl, s.shaders.grid_vertex, look.shaders.stats_fragment)];
      this.programs.set(look, programs);
    }
    [this.main, this.stats] = programs;
    this.applySettings(look.uniforms);
    gl.useProgram(this.grid);
    for (const u of look.grid_uniforms) setUniform(gl, this.grid, u);
    // F_t ping-pong, in the look's channels.
    if (channels !== look.texture_channels) {
      this.textures.forEach((t) => gl.deleteTexture(t));
      this.fbs.forEach((f) => gl.deleteFramebuffer(f));
      const [internal, format] = look.texture_channels === 4 ? [gl.RGBA16F, gl.RGBA] : [gl.RG16F, gl.RG];
      this.textures = [0, 1].map(() => texture(gl, s.width, s.height, internal, format, gl.HALF_FLOAT, true));
      this.fbs = this.textures.map((t) => framebuffer(gl, [t, this.output], this.depth));
    }
    const scale = look.uniforms.find((u) => u.name === "u_noise_scale");
    this.setNoiseScale(scale ? scale.values[0] : 1, look.phase_size);
    this.reset();
  }

  /// The noise scale s in pixels, at least the finest look's: the grid of
  /// floor(size / s) + 2 points a side takes the first of the page's phases,
  /// as NoiseGrid numbers them (row by row), so it is ibfvs render's grid.
  setNoiseScale(scale: number, size?: [number, number]): void {
    const gl = this.gl, s = this.scene;
    const [cols, rows] = size ?? [Math.min(Math.floor(s.width / scale) + 2, s.phase_size[0]),
                                  Math.min(Math.floor(s.height / scale) + 2, s.phase_size[1])];
    if (this.phases) gl.deleteTexture(this.phases);
    if (this.gridTexture) gl.deleteTexture(this.gridTexture);
    if (this.gridFb) gl.deleteFramebuffer(this.gridFb);
    this.phases = texture(gl, cols, rows, gl.R32F, gl.RED, gl.FLOAT, false,
                          this.allPhases.subarray(0, cols * rows));
    // The grid pass's target: G_ij, sampled bilinearly and repeating (eq. 7).
    this.gridTexture = texture(gl, cols, rows, gl.R32F, gl.RED, gl.FLOAT, true);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
    this.gridFb = framebuffer(gl, [this.gridTexture], null);
    this.phaseSize = [cols, rows];
    this.applySettings([
      { name: "u_noise_scale", type: "float", values: [scale] },
      { name: "u_phase_size", type: "int", values: [cols, rows] },
    ]);
  }

  /// Time t in steps (looping), as Session::seek: the field between step
  /// floor(t) and the next.
  setTime(t: number): void {
    const gl = this.gl, n = this.scene.steps;
    t = ((t % n) + n) % n;
    const step = Math.floor(t) % n;
    this.fieldMix = n > 1 ? t - Math.floor(t) : 0;
    if (step === this.step) return;
    this.step = step;
    const bytes = this.scene.vertex_count * 8; // four half floats per vector
    gl.bindVertexArray(this.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vectorBuffer);
    gl.vertexAttribPointer(2, 4, gl.HALF_FLOAT, false, 0, step * bytes);
    gl.vertexAttribPointer(4, 4, gl.HALF_FLOAT, false, 0, ((step + 1) % n) * bytes);
    gl.bindVertexArray(null);
  }

  applySettings(uniforms: Uniform[]): void {
    this.gl.useProgram(this.main);
    for (const u of uniforms) setUniform(this.gl, this.main, u);
  }

  /// F_t stops as it is and is mapped onto the surface as seen now, while the
  /// view moves (IbfvsRenderer::lock).
  lock(): void {
    if (this.locked) return;
    this.locked = true;
    this.lockViewProjection = this.previousViewProjection;
  }

  reset(): void {
    const gl = this.gl;
    for (const fb of this.fbs) this.clear(fb);
    if (this.cells) {
      gl.bindTexture(gl.TEXTURE_2D, this.textures[0]);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, this.scene.width, this.scene.height, gl.RGBA, gl.FLOAT,
                       this.cells);
    }
    this.locked = false;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.statsFb);
    gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]); // no statistics before the first frame
    this.current = 0;
    this.frame = 0;
    this.previousViewProjection = null;
  }

  private clear(fb: WebGLFramebuffer): void {
    const gl = this.gl, b = this.look.background, d = this.scene.no_depth;
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.clearBufferfv(gl.COLOR, 0, this.look.colour_texture ? [b[0], b[1], b[2], d] : [b[0], d, 0, 0]);
    gl.clearBufferfv(gl.COLOR, 1, [b[0], b[1], b[2], 1]);
    gl.clearBufferfi(gl.DEPTH_STENCIL, 0, 1, 0);
  }

  /// One frame seen through `view` and `projection`; dt 0 stands still.
  render(view: mat4, projection: mat4, dt: number): void {
    const gl = this.gl, s = this.scene;
    const vp = mat4.multiply(mat4.create(), projection, view);
    const next = 1 - this.current;
    const noiseTime = this.look.noise_rate * this.frame;
    gl.disable(gl.BLEND);
    // The grid pass: G_ij of this frame.
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.gridFb!);
    gl.viewport(0, 0, this.phaseSize[0], this.phaseSize[1]);
    gl.disable(gl.DEPTH_TEST);
    gl.disable(gl.CULL_FACE);
    gl.useProgram(this.grid);
    gl.uniform1f(locate(gl, this.grid, "u_noise_time"), noiseTime);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.phases!);
    gl.bindVertexArray(this.empty);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    // The IBFVS pass into F_t (next) and F.
    this.clear(this.fbs[next]);
    gl.viewport(0, 0, s.width, s.height);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    if (s.cull !== 0) {
      gl.enable(gl.CULL_FACE);
      gl.cullFace(s.cull > 0 ? gl.BACK : gl.FRONT);
    }
    const p = this.main;
    gl.useProgram(p);
    const at = (n: string) => locate(gl, p, n);
    gl.uniformMatrix4fv(at("u_view_projection"), false, vp);
    const advect = this.locked && this.lockViewProjection ? this.lockViewProjection
      : this.look.advect_previous && this.previousViewProjection ? this.previousViewProjection : vp;
    gl.uniformMatrix4fv(at("u_advect_view_projection"), false, advect);
    gl.uniformMatrix4fv(at("u_view"), false, view);
    const pr = projection;
    if (pr[15] === 0) gl.uniform2f(at("u_clip_to_depth"), 0, 1);
    else gl.uniform2f(at("u_clip_to_depth"), -1 / pr[10], pr[14] / pr[10]);
    gl.uniform1f(at("u_dt"), this.locked ? 0 : dt);
    gl.uniform1f(at("u_probe"), s.probe);
    gl.uniform1f(at("u_field_mix"), this.fieldMix);
    gl.uniform2f(at("u_texture_shift"), 0, 0);
    gl.uniform2f(at("u_noise_shift"), 0, 0);
    gl.uniform1i(at("u_locked"), this.locked ? 1 : 0);
    gl.uniform1f(at("u_noise_time"), noiseTime);
    const bind = (unit: number, t: WebGLTexture) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, t);
    };
    bind(0, this.textures[this.current]);
    bind(1, this.gridTexture!);
    bind(2, this.colorMap);
    if (this.surfaceImage) bind(3, this.surfaceImage);
    bind(4, this.statsTexture);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbs[next]);
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, s.index_count, gl.UNSIGNED_INT, 0);
    gl.disable(gl.CULL_FACE);
    gl.disable(gl.DEPTH_TEST);
    // The statistics of the contrast stage, every few frames, blended into a running average.
    if (this.frame % s.stats.every === 0) {
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.statsFb);
      gl.viewport(0, 0, 1, 1);
      gl.useProgram(this.stats);
      gl.uniform2f(locate(gl, this.stats, "u_image_size"), s.width, s.height);
      gl.uniform1i(locate(gl, this.stats, "u_stats_size"), s.stats.size);
      const f = this.frame;
      gl.uniform2f(locate(gl, this.stats, "u_offset"), (f * 0.618034) % 1, (f * 0.381966) % 1);
      bind(0, this.textures[next]);
      bind(1, this.output);
      gl.enable(gl.BLEND);
      gl.blendColor(0, 0, 0, s.stats.weight);
      gl.blendFunc(gl.CONSTANT_ALPHA, gl.ONE_MINUS_CONSTANT_ALPHA);
      gl.bindVertexArray(this.empty);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      gl.disable(gl.BLEND);
    }
    if (!this.locked) {  // a locked F_t stays where it is; F is shared
      this.current = next;
      this.previousViewProjection = vp;
    }
    ++this.frame;
  }

  /// F onto the canvas (same size).
  present(): void {
    const gl = this.gl;
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.fbs[this.current]);
    gl.readBuffer(gl.COLOR_ATTACHMENT1);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
    const w = this.scene.width, h = this.scene.height;
    gl.blitFramebuffer(0, 0, w, h, 0, 0, w, h, gl.COLOR_BUFFER_BIT, gl.NEAREST);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }
}

// ---------------------------------------------------------------- the camera and input

/// Turns, pans and zooms about the scene's centre: the view turned in eye
/// space about the centre, the image scaled and moved in clip space (the
/// projection's depth, and so the depth test, unchanged).
class Navigation {
  turn = mat4.create();
  zoom = 1;
  pan = [0, 0];
  orbit = 0; // degrees the camera has orbited (the scene's orbit)
  private base: Camera;
  constructor(private scene: SceneHeader) {
    this.base = scene;
  }
  /// Starts again from `base`'s camera (the scene's, or its lock view).
  moveTo(base: Camera): void {
    this.base = base;
    this.turn = mat4.create();
    this.zoom = 1;
    this.pan = [0, 0];
    this.orbit = 0;
  }
  view(): mat4 {
    // The orbit turns the eye about the vertical through the look-at point
    // (Camera::orbit): the world the other way.
    const v0 = mat4.clone(this.base.view as unknown as mat4);
    const o = this.scene.orbit;
    if (o && this.orbit !== 0) {
      const t = this.base.target as unknown as vec3;
      mat4.translate(v0, v0, t);
      mat4.rotate(v0, v0, (-this.orbit * Math.PI) / 180, o.up as unknown as vec3);
      mat4.translate(v0, v0, vec3.negate(vec3.create(), t));
    }
    const c = vec3.transformMat4(vec3.create(), this.scene.centre as unknown as vec3, v0);
    const m = mat4.fromTranslation(mat4.create(), c);
    mat4.multiply(m, m, this.turn);
    mat4.translate(m, m, vec3.negate(vec3.create(), c));
    return mat4.multiply(m, m, v0);
  }
  projection(): mat4 {
    const m = mat4.fromTranslation(mat4.create(), [this.pan[0], this.pan[1], 0]);
    mat4.scale(m, m, [this.zoom, this.zoom, 1]);
    return mat4.multiply(m, m, this.base.projection as unknown as mat4);
  }
  drag(dx: number, dy: number): void {
    // Degrees per pixel as ibfvs view's.
    const r = mat4.create();
    mat4.rotateY(r, r, dx * 0.005);
    mat4.rotateX(r, r, dy * 0.005);
    mat4.multiply(this.turn, r, this.turn);
  }
}

// ---------------------------------------------------------------- start

export function start(root: HTMLElement, scene: SceneHeader, data: ArrayBuffer): PageRenderer | null {
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
  const panel = document.createElement("div");
  panel.className = "ibfvs-panel";
  root.appendChild(panel);
  const nav = new Navigation(scene);
  let playing = true;
  const play = document.createElement("button");
  play.textContent = "Pause";
  play.addEventListener("click", () => {
    playing = !playing;
    play.textContent = playing ? "Pause" : "Play";
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
  let dtFactor = 1;
  const controls = document.createElement("span");
  controls.style.display = "contents"; // its sliders flow in the panel
  const lookControls = () => {
    controls.replaceChildren();
    dtFactor = 1;
    const uniform = (name: string) => renderer.look.uniforms.find((u) => u.name === name);
    for (const [name, label] of [["u_alpha", "alpha"], ["u_beta", "beta"]] as const) {
      const u = uniform(name);
      if (!u) continue;
      slider(controls, label, 0, 1, u.values[0], (v) => {
        u.values[0] = v;
        renderer.applySettings([u]);
      });
    }
    // The step: pixels per frame of every point (image-space normalisation),
    // else a factor on the look's dt.
    const imageStep = uniform("u_image_step");
    if (imageStep && imageStep.values[0] > 0) {
      slider(controls, "step (px)", 0.25, 8, imageStep.values[0], (v) => {
        imageStep.values[0] = v;
        renderer.applySettings([imageStep]);
      });
    } else {
      slider(controls, "speed", 0, 4, 1, (v) => (dtFactor = v));
    }
    // The noise scale, from the look's own up (the phases cover finer grids only).
    const noiseScale = uniform("u_noise_scale");
    if (noiseScale) {
      const base = noiseScale.values[0];
      slider(controls, "noise scale (px)", base, 6 * base, base, (v) => renderer.setNoiseScale(v));
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
    menu.addEventListener("change", () => {
      renderer.setLook(parseInt(menu.value, 10));
      lookControls();
    });
    wrap.appendChild(menu);
    panel.appendChild(wrap);
  }
  lookControls();
  panel.appendChild(controls);
  // Time steps: a slider over the steps, moving while playing.
  let time = 0;
  let timeSlider: HTMLInputElement | null = null;
  if (scene.steps > 1) {
    timeSlider = slider(panel, "time step", 0, scene.steps, 0, (v) => {
      time = v;
      renderer.setTime(time);
    });
    timeSlider.step = "0.01";
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
  // A WebM of the canvas while recording (MediaRecorder), saved on stop.
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
        a.download = scene.name + ".webm";
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
  document.addEventListener("keydown", (e) => {
    if (e.key === " ") play.click();
  });

  const tick = () => {
    if (playing) {
      if (scene.steps > 1) {
        time = (time + 1 / scene.frames_per_step) % scene.steps;
        renderer.setTime(time);
        if (timeSlider) timeSlider.value = String(time);
      }
      if (scene.lock && renderer.frame === scene.lock.frame && !renderer.locked) {
        renderer.lock(); // as Session::advance: before the lock frame is drawn
        nav.moveTo(scene.lock);
      }
      if (scene.orbit && renderer.frame > 0) nav.orbit += scene.orbit.degrees;
      renderer.render(nav.view(), nav.projection(), renderer.look.dt * dtFactor);
    }
    renderer.present();
    const w = window as unknown as { ibfvsFrames: number; ibfvsTime: number; ibfvsLocked: boolean };
    w.ibfvsFrames = renderer.frame;
    w.ibfvsLocked = renderer.locked;
    w.ibfvsTime = time;
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  return renderer;
}

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
