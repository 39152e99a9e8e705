// The runtime of an ibfvs page (docs/web.md). The page holds the prepared
// scene (a JSON header and one base64 block of binary arrays) and the GLSL
// ES 3.00 sources that ibfvs's one shader generator emitted for it; this
// script runs the same passes as the OpenGL renderer (src/render/
// ibfvs_renderer.cpp): the noise grid, the IBFVS pass into F_t and F, the
// contrast statistics, and shows F. Only what WebGL2 needs differently is
// here: sampler units set by name, extension checks, the canvas.
//
// Sections: the renderer; the camera. The page around it (its elements, the
// input, recording, the loop) is page.ts, the scene format format.ts, the
// WebGL objects webgl.ts.
import { mat4, vec3 } from "gl-matrix";
import { type Camera, type Look, type PlannedPass, type SceneHeader, type Uniform, f32, halfToFloat, u32, view }
  from "./format";
import { Surfaces } from "./surfaces";
import { bindSampler, compile, framebuffer, locate, setUniform, texture } from "./webgl";

/// The tap texture's depth map, (ln lo, 1 / (ln hi - ln lo)) from the projection's near and far
/// planes, lo at least hi / 1000: tap_depth_map() of core/texture/display.cpp (column-major).
function tapDepthMap(pr: ArrayLike<number>): [number, number] {
  let near: number, far: number;
  if (pr[15] === 0) {
    near = pr[14] / (pr[10] - 1);
    far = pr[14] / (pr[10] + 1);
  } else {
    near = (pr[14] + 1) / pr[10];
    far = (pr[14] - 1) / pr[10];
  }
  if (!Number.isFinite(far) || !(far > 0)) far = Number.isFinite(near) && near > 0 ? 1e3 * near : 1;
  const lo = Math.log(Math.max(near, far * 1e-3, 1e-30)), hi = Math.log(far);
  return [lo, hi > lo ? 1 / (hi - lo) : 1];
}

export class PageRenderer {
  readonly gl: WebGL2RenderingContext;
  readonly scene: SceneHeader;
  look: Look;
  frame = 0;
  private main!: WebGLProgram;
  private grid: WebGLProgram;
  private stats!: WebGLProgram;
  private display: WebGLProgram | null = null; // the display pass, with a tap texture
  // compiled looks: main, stats, display
  private programs = new Map<Look, [WebGLProgram, WebGLProgram, WebGLProgram | null]>();
  private surfaces: Surfaces;
  private empty: WebGLVertexArrayObject;
  private textures: WebGLTexture[] = [];
  private taps: WebGLTexture[] = []; // beside F_t when the look has a tap texture (RGBA8), else none
  private tapDepth: [number, number][] = [[0, 0], [0, 0]]; // the depth map taps[i] was written with
  // With a tap texture the IBFVS pass leaves the display pass ((1 - beta) F_s, beta) and the
  // seed (the filter's first tap, t(x)'s depth, the displacement): IbfvsRenderer::display_pass.
  private base: WebGLTexture | null = null;
  private seed: WebGLTexture | null = null;
  private output: WebGLTexture;
  private outputFb: WebGLFramebuffer;
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
  private step = -1;
  private fieldMix = 0;
  private previousViewProjection: mat4 | null = null;
  private cells: Float32Array | null = null; // F_t's first texels (random cells), or null
  locked = false;
  private lockViewProjection: mat4 | null = null;
  // The scene's overlay (its topology: render/topology_overlay.h), a set of quads a step.
  private overlay: { program: WebGLProgram; steps: { vao: WebGLVertexArrayObject; count: number }[] } | null = null;

  constructor(gl: WebGL2RenderingContext, scene: SceneHeader, data: ArrayBuffer) {
    this.gl = gl;
    this.scene = scene;
    const s = scene, w = s.width, h = s.height;
    this.look = s.looks[0];
    this.grid = compile(gl, s.shaders.grid_vertex, s.shaders.grid_fragment);

    const a = s.arrays;
    this.surfaces = new Surfaces(gl, scene, data);
    this.setTime(0);
    this.empty = gl.createVertexArray()!;

    // F and the depth; F_t, the grid and the programs come with the look.
    this.output = texture(gl, w, h, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, false);
    this.depth = texture(gl, w, h, gl.DEPTH_COMPONENT24, gl.DEPTH_COMPONENT, gl.UNSIGNED_INT, false);
    this.outputFb = framebuffer(gl, [this.output], this.depth);
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
    if (s.overlay) this.overlay = this.makeOverlay(data);
    this.setLook(0);
  }

  /// The overlay's program and each step's quads (OverlayVertex: 25 floats a corner).
  private makeOverlay(data: ArrayBuffer): NonNullable<PageRenderer["overlay"]> {
    const gl = this.gl, o = this.scene.overlay!;
    const program = compile(gl, o.vertex, o.fragment);
    const steps = o.steps.map((step) => {
      const vao = gl.createVertexArray()!;
      gl.bindVertexArray(vao);
      const corners = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, corners);
      gl.bufferData(gl.ARRAY_BUFFER, view(data, step.vertices, f32, 4), gl.STATIC_DRAW);
      // point, other, corner, colour, shape, point_to, other_to, point_bulge, other_bulge, span
      [[0, 3, 0], [1, 3, 3], [2, 2, 6], [3, 3, 8], [4, 1, 11], [5, 3, 12], [6, 3, 15], [7, 3, 18],
       [8, 3, 21], [9, 1, 24]].forEach(([location, size, at]) => {
        gl.enableVertexAttribArray(location);
        gl.vertexAttribPointer(location, size, gl.FLOAT, false, 100, at * 4);
      });
      const indices = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indices);
      const ids = view(data, step.indices, u32, 4);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, ids, gl.STATIC_DRAW);
      gl.bindVertexArray(null);
      return { vao, count: ids.length };
    });
    return { program, steps };
  }

  /// Shows the scene in look `index` (a style over the same data), from a
  /// fresh texture: its programs (compiled once), F_t's channels, its noise
  /// grid and its uniforms.
  setLook(index: number): void {
    const gl = this.gl, s = this.scene, look = s.looks[index];
    const layout = this.textures.length ? [this.look.texture_channels, this.look.tap_texture] : [];
    this.look = look;
    let programs = this.programs.get(look);
    if (!programs) {
      programs = [compile(gl, look.shaders.vertex, look.shaders.fragment),
                  compile(gl, s.shaders.grid_vertex, look.shaders.stats_fragment),
                  look.tap_texture ? compile(gl, s.shaders.display_vertex, look.shaders.display_fragment) : null];
      this.programs.set(look, programs);
    }
    [this.main, this.stats, this.display] = programs;
    this.applySettings(look.uniforms);
    gl.useProgram(this.grid);
    for (const u of look.grid_uniforms) setUniform(gl, this.grid, u);
    // F_t ping-pong, in the look's channels.
    if (layout[0] !== look.texture_channels || layout[1] !== look.tap_texture) {
      [...this.textures, ...this.taps, this.base, this.seed].forEach((t) => t && gl.deleteTexture(t));
      this.fbs.forEach((f) => gl.deleteFramebuffer(f));
      const [internal, format] = look.texture_channels === 4 ? [gl.RGBA16F, gl.RGBA] : [gl.RG16F, gl.RG];
      this.textures = [0, 1].map(() => texture(gl, s.width, s.height, internal, format, gl.HALF_FLOAT, true));
      this.taps = look.tap_texture
        ? [0, 1].map(() => texture(gl, s.width, s.height, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, true))
        : [];
      this.base = look.tap_texture ? texture(gl, s.width, s.height, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, false) : null;
      this.seed = look.tap_texture ? texture(gl, s.width, s.height, gl.RGBA16F, gl.RGBA, gl.HALF_FLOAT, false) : null;
      this.fbs = this.textures.map((t, i) =>
        framebuffer(gl, this.taps.length ? [t, this.base!, this.taps[i], this.seed!] : [t, this.output], this.depth));
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
    this.surfaces.setStep(step, this.previousViewProjection !== null);
  }

  applySettings(uniforms: Uniform[]): void {
    for (const p of this.display ? [this.main, this.display] : [this.main]) {
      this.gl.useProgram(p);
      for (const u of uniforms) setUniform(this.gl, p, u);
    }
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
    if (this.taps.length) gl.clearBufferfv(gl.COLOR, 2, [0.5, 0, 0.5, 0.5]); // no depth, no direction
    gl.clearBufferfi(gl.DEPTH_STENCIL, 0, 1, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.outputFb);
    gl.clearBufferfv(gl.COLOR, 0, [b[0], b[1], b[2], 1]);
  }

  /// One frame seen through `view` and `projection`; dt 0 stands still.
  /** The next frame of the page's own run, in Session::advance's order: at
   * the lock frame the texture locks and the view moves to the lock view
   * (before that frame is drawn); after frame 0 the camera orbits. */
  advance(nav: Navigation, dtFactor: number): void {
    const scene = this.scene;
    if (scene.lock && this.frame === scene.lock.frame && !this.locked) {
      this.lock();
      nav.moveTo(scene.lock);
    }
    if (scene.orbit && this.frame > 0) nav.orbit += scene.orbit.degrees;
    this.render(nav.view(), nav.projection(), this.look.dt * dtFactor);
  }

  render(view: mat4, projection: mat4, dt: number): void {
    const gl = this.gl, s = this.scene;
    const vp = mat4.multiply(mat4.create(), projection, view);
    const next = 1 - this.current;
    gl.disable(gl.BLEND);
    // The frame's passes in the plan's order (render/frame_plan.h, in the header),
    // each where its `when` says.
    for (const pass of s.plan) {
      if (!this.runs(pass.when)) continue;
      switch (pass.name) {
        case "grid": this.gridPass(pass, next); break;
        case "ibfvs": this.ibfvsPass(pass, next, view, projection, vp, dt); break;
        case "display": this.displayPass(pass, next); break;
        case "stats": this.statsPass(pass, next); break;
        default: throw new Error(`the page's plan has a pass this runtime does not run: ${pass.name}`);
      }
    }
    this.overlayPass(view, projection);
    gl.disable(gl.DEPTH_TEST);
    if (!this.locked) {  // a locked F_t stays where it is; F is shared
      this.current = next;
      this.previousViewProjection = vp;
      this.surfaces.drawnFrame(this.fieldMix);
    }
    ++this.frame;
  }

  /// Whether this frame runs a pass of the plan: its `when` over the look's facts,
  /// the rule of pass_runs in render/frame_plan.cpp.
  private runs(when: string): boolean {
    const f = this.look.facts;
    switch (when) {
      case "": return true;
      case "image_noise": return f.image_noise;
      case "taps": return f.taps;
      case "contrast": return f.contrast && this.frame % this.scene.stats.every === 0;
      default: throw new Error(`the page's plan has a condition this runtime does not know: ${when}`);
    }
  }

  /// The image of the plan named `name` in a frame that draws F_t into
  /// textures[now] from textures[last] (IbfvsRenderer::image).
  private image(name: string, now: number, last: number): WebGLTexture | null {
    switch (name) {
      case "phases": return this.phases;
      case "grid": return this.gridTexture;
      case "texture.last": return this.textures[last];
      case "texture.now": return this.textures[now];
      case "taps.last": return this.taps[last] ?? null;
      case "taps.now": return this.taps[now] ?? null;
      case "color_map": return this.colorMap;
      case "surface_image": return this.surfaceImage;
      case "stats": return this.statsTexture;
      case "seed": return this.seed;
      case "base": return this.base;
      case "output": return this.output;
      default: throw new Error(`the page's plan names an image this runtime does not have: ${name}`);
    }
  }

  /// Binds what a pass's samplers read, by the plan.
  private bindReads(pass: PlannedPass, program: WebGLProgram, now: number): void {
    for (const read of pass.reads) {
      const t = this.image(read.image, now, 1 - now);
      if (t) bindSampler(this.gl, program, read.sampler, t);
    }
  }

  /// The grid pass: G_ij of this frame.
  private gridPass(pass: PlannedPass, next: number): void {
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.gridFb!);
    gl.viewport(0, 0, this.phaseSize[0], this.phaseSize[1]);
    gl.disable(gl.DEPTH_TEST);
    gl.disable(gl.CULL_FACE);
    gl.useProgram(this.grid);
    gl.uniform1f(locate(gl, this.grid, "u_noise_time"), this.look.noise_rate * this.frame);
    this.bindReads(pass, this.grid, next);
    gl.bindVertexArray(this.empty);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  /// The IBFVS pass into F_t (next) and F.
  private ibfvsPass(pass: PlannedPass, next: number, view: mat4, projection: mat4, vp: mat4, dt: number): void {
    const gl = this.gl, s = this.scene;
    this.clear(this.fbs[next]);
    gl.viewport(0, 0, s.width, s.height);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
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
    // This step's mesh; a moving surface's from where the last frame drew it
    // (where it was this mesh and motion enters: not locked, not the first
    // frame, advecting in the last view).
    const compensate = this.look.carry_surface && this.previousViewProjection !== null && !this.locked;
    const mesh = this.surfaces.bind(compensate, this.fieldMix, at("u_drawn_mix"));
    if (mesh.cull !== 0) {
      gl.enable(gl.CULL_FACE);
      gl.cullFace(mesh.cull > 0 ? gl.BACK : gl.FRONT);
    }
    gl.uniform2f(at("u_texture_shift"), 0, 0);
    gl.uniform2f(at("u_noise_shift"), 0, 0);
    gl.uniform1i(at("u_locked"), this.locked ? 1 : 0);
    gl.uniform1f(at("u_noise_time"), this.look.noise_rate * this.frame);
    this.tapDepth[next] = tapDepthMap(pr);
    gl.uniform2f(at("u_tap_depth"), ...this.tapDepth[next]);
    this.bindReads(pass, p, next);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.fbs[next]);
    gl.drawElements(gl.TRIANGLES, mesh.count, gl.UNSIGNED_INT, 0);
    gl.disable(gl.CULL_FACE);
  }

  /// The display pass: once per pixel of the surface (a triangle on the far
  /// plane, depth test GREATER), into F.
  private displayPass(pass: PlannedPass, next: number): void {
    const gl = this.gl, d = this.display!;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.outputFb);
    gl.depthFunc(gl.GREATER);
    gl.depthMask(false);
    gl.useProgram(d);
    gl.uniform2f(locate(gl, d, "u_texture_shift"), 0, 0);
    gl.uniform2f(locate(gl, d, "u_tap_depth"), ...this.tapDepth[this.current]); // the last frame's taps
    this.bindReads(pass, d, next);
    gl.bindVertexArray(this.empty);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.depthMask(true);
    gl.depthFunc(gl.LESS);
  }

  /// The statistics of the contrast stage, blended into a running average.
  private statsPass(pass: PlannedPass, next: number): void {
    const gl = this.gl, s = this.scene;
    gl.disable(gl.DEPTH_TEST);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.statsFb);
    gl.viewport(0, 0, 1, 1);
    gl.useProgram(this.stats);
    gl.uniform2f(locate(gl, this.stats, "u_image_size"), s.width, s.height);
    gl.uniform1i(locate(gl, this.stats, "u_stats_size"), s.stats.size);
    const f = this.frame;
    gl.uniform2f(locate(gl, this.stats, "u_offset"), (f * 0.618034) % 1, (f * 0.381966) % 1);
    this.bindReads(pass, this.stats, next);
    gl.enable(gl.BLEND);
    gl.blendColor(0, 0, 0, s.stats.weight);
    gl.blendFunc(gl.CONSTANT_ALPHA, gl.ONE_MINUS_CONSTANT_ALPHA);
    gl.bindVertexArray(this.empty);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.disable(gl.BLEND);
  }

  /// The overlay over F where the surface does not hide it (Session::draw_overlay,
  /// TopologyOverlay::draw): depth test LEQUAL, no depth or alpha writes.
  private overlayPass(view: mat4, projection: mat4): void {
    const o = this.overlay;
    if (!o) return;
    const step = o.steps[Math.min(this.step, o.steps.length - 1)];
    if (!step.count) return;
    const gl = this.gl, s = this.scene, p = o.program, at = (n: string) => locate(gl, p, n);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.outputFb);
    gl.viewport(0, 0, s.width, s.height);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    gl.depthMask(false);
    gl.colorMask(true, true, true, false);
    gl.disable(gl.CULL_FACE);
    gl.useProgram(p);
    gl.uniformMatrix4fv(at("u_view"), false, view);
    gl.uniformMatrix4fv(at("u_projection"), false, projection);
    gl.uniform2f(at("u_viewport"), s.width, s.height);
    gl.uniform1f(at("u_line_width"), s.overlay!.line_width);
    gl.uniform1f(at("u_glyph"), s.overlay!.glyph);
    gl.uniform1f(at("u_lift"), s.overlay!.lift);
    gl.uniform1f(at("u_mix"), this.fieldMix);
    gl.bindVertexArray(step.vao);
    gl.drawElements(gl.TRIANGLES, step.count, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
    gl.colorMask(true, true, true, true);
    gl.depthMask(true);
    gl.depthFunc(gl.LESS);
  }

  /// F onto the canvas (same size).
  present(): void {
    const gl = this.gl;
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.outputFb);
    gl.readBuffer(gl.COLOR_ATTACHMENT0);
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
export class Navigation {
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
