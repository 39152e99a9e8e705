// The format of an ibfvs page (docs/web.md), as src/render/web_page.cpp
// writes it: a JSON header and one base64 block of binary arrays, some
// through meshoptimizer's codecs.
import { MeshoptDecoder } from "meshoptimizer/decoder";

// ---------------------------------------------------------------- the scene format

export interface Uniform {
  name: string;
  type: "float" | "int" | "uint";
  values: number[];
  array?: boolean;
}

export interface ArrayRef {
  offset: number; // bytes into the binary block
  length: number; // elements, or with a codec its encoded bytes
  codec?: "vertex" | "index"; // meshoptimizer's codecs (per-vertex arrays, triangle indices)
  stride?: number; // bytes a vertex (the vertex codec)
  elements?: number; // elements once decoded
}

/// An array of the block as `T` (Uint16Array, Float32Array, ...), decoded
/// where the page wrote it through a meshoptimizer codec.
export function view<T>(data: ArrayBuffer, ref: ArrayRef,
                 make: (buffer: ArrayBuffer, offset: number, length: number) => T, bytesEach: number): T {
  if (!ref.codec) return make(data, ref.offset, ref.length);
  const source = new Uint8Array(data, ref.offset, ref.length);
  const target = new Uint8Array(ref.elements! * bytesEach);
  if (ref.codec === "vertex")
    MeshoptDecoder.decodeVertexBuffer(target, target.length / ref.stride!, ref.stride!, source);
  else MeshoptDecoder.decodeIndexBuffer(target, ref.elements!, 4, source);
  return make(target.buffer, 0, ref.elements!);
}
export const u16 = (b: ArrayBuffer, o: number, n: number) => new Uint16Array(b, o, n);
export const i8 = (b: ArrayBuffer, o: number, n: number) => new Int8Array(b, o, n);
export const u32 = (b: ArrayBuffer, o: number, n: number) => new Uint32Array(b, o, n);
export const f32 = (b: ArrayBuffer, o: number, n: number) => new Float32Array(b, o, n);

/// A camera of the page: its matrices (column-major 4x4) and look-at point.
export interface Camera {
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
  tap_texture: boolean; // beside F_t, the display filter's taps: RGBA8 (sharpened value, log depth, direction)
  advect_previous: boolean;
  phase_size: [number, number]; // its noise grid: the first columns x rows of the page's phases
  // display_fragment: the display pass, with a tap texture (else empty)
  shaders: { vertex: string; fragment: string; stats_fragment: string; display_fragment: string };
  uniforms: Uniform[];
  grid_uniforms: Uniform[];
}

/// A step's own mesh (a changing mesh).
export interface StepMesh {
  vertex_count: number;
  index_count: number;
  cull: number;
  positions: ArrayRef; // uint16 x 4, in the box of arrays.positions
  normals: ArrayRef; // int8 x 4
  vectors: ArrayRef; // float16 x 4, its step's
  indices: ArrayRef; // uint32
  scalars?: ArrayRef; // float32 x 2 (colour, beta)
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
  shaders: { grid_vertex: string; grid_fragment: string; display_vertex: string };
  looks: Look[]; // the scene's own first
  vertex_count: number;
  steps: number; // time steps of the field (1: steady)
  step_mesh?: number[]; // per step: 0 the first step's mesh, k > 0 arrays.meshes[k - 1]
  frames_per_step: number;
  index_count: number;
  phase_size: [number, number]; // of the phases array (the finest look's grid)
  arrays: {
    positions: ArrayRef & { min: number[]; max: number[] }; // uint16 x 4 (the last 0), in the box
    normals: ArrayRef; // int8 x 4 (snorm)
    vectors: ArrayRef; // float16 x 4, every time step one after the other
    scalars?: ArrayRef & { steps: number }; // float32 x 2 (colour, beta) per vertex, for each of `steps` steps (1: all alike)
    indices: ArrayRef; // uint32
    phases: ArrayRef; // uint16, phi * 65535
    color_map: ArrayRef; // uint8 RGBA x 256
    // The surface colour, an equirectangular image (uint8 RGBA, the bottom row first)
    surface_image?: ArrayRef & { width: number; height: number };
    // F_t's first colours, one per noise cell of `scale` pixels, float16 RGB_ by rows of `columns`
    cells?: ArrayRef & { columns: number; scale: number };
    // A surface that moves: the vertices that move at some step (uint32), and
    // sets of their points (uint16 x 4 in the box of `positions`) and normals
    // (int8 x 4), one set after the other; step k takes set sets[k] (a step
    // like the one before it shares its set). The looks' vertex shaders then
    // read each vertex at this step and the next, and where the last frame drew it.
    motion?: { moving: ArrayRef; positions: ArrayRef; normals: ArrayRef; sets: number[] };
    // The steps whose triangles are their own (a changing mesh), in step
    // order: each as the first step's (positions in the same box), with its
    // one step's vectors and colours.
    meshes?: StepMesh[];
  };
}

/// An IEEE half float's value.
export function halfToFloat(h: number): number {
  const exponent = (h >> 10) & 31, fraction = h & 1023, sign = h & 0x8000 ? -1 : 1;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction ? NaN : sign * Infinity;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

export function decodeBase64(text: string): ArrayBuffer {
  const binary = atob(text.replace(/\s+/g, ""));
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}
