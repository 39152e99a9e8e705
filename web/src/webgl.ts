// WebGL2 objects for the page's renderer: programs (sampler units from the
// generator's BINDING(UNIT_NAME) marks), textures bound to samplers by name,
// uniforms by name, textures, framebuffers.
import type { Uniform } from "./format";

// ---------------------------------------------------------------- WebGL objects

export function compile(gl: WebGL2RenderingContext, vertex: string, fragment: string): WebGLProgram {
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
  // generator's BINDING(UNIT_NAME) marks and its prelude defines each
  // UNIT_NAME (the library's one table, texture_units.h): the units are set
  // from them by name, and kept for bindSampler.
  gl.useProgram(program);
  const units = new Map<string, number>();
  for (const source of [vertex, fragment]) {
    const defined = new Map<string, number>();
    for (const m of source.matchAll(/#define (UNIT_\w+) (\d+)/g)) defined.set(m[1], parseInt(m[2], 10));
    for (const m of source.matchAll(/BINDING\((\w+)\)\s+uniform\s+\w+\s+(\w+)/g)) {
      const unit = defined.get(m[1]);
      if (unit === undefined) throw new Error(`shader: ${m[2]}'s unit ${m[1]} is not defined`);
      units.set(m[2], unit);
      gl.uniform1i(gl.getUniformLocation(program, m[2]), unit);
    }
  }
  samplerUnits.set(program, units);
  return program;
}

// Each program's samplers and their units (compile).
const samplerUnits = new WeakMap<WebGLProgram, Map<string, number>>();

/** Binds `t` to the sampler `name` of `program` (to its unit); nothing for a sampler the program does not declare. */
export function bindSampler(gl: WebGL2RenderingContext, program: WebGLProgram, name: string, t: WebGLTexture): void {
  const unit = samplerUnits.get(program)?.get(name);
  if (unit === undefined) return;
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(gl.TEXTURE_2D, t);
}

// Uniform locations, looked up once per program and name (not every frame).
const locations = new WeakMap<WebGLProgram, Map<string, WebGLUniformLocation | null>>();
export function locate(gl: WebGL2RenderingContext, program: WebGLProgram, name: string): WebGLUniformLocation | null {
  let known = locations.get(program);
  if (!known) locations.set(program, (known = new Map()));
  if (!known.has(name)) known.set(name, gl.getUniformLocation(program, name));
  return known.get(name)!;
}

export function setUniform(gl: WebGL2RenderingContext, program: WebGLProgram, u: Uniform): void {
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

export function texture(gl: WebGL2RenderingContext, w: number, h: number, internal: number, format: number,
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

export function framebuffer(gl: WebGL2RenderingContext, colours: WebGLTexture[], depth: WebGLTexture | null): WebGLFramebuffer {
  const fb = gl.createFramebuffer()!;
  gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  colours.forEach((t, i) => gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, t, 0));
  if (depth) gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, depth, 0);
  gl.drawBuffers(colours.map((_, i) => gl.COLOR_ATTACHMENT0 + i));
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
    throw new Error("this browser cannot render into float textures (framebuffer incomplete)");
  return fb;
}
