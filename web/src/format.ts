// The format of an ibfvs page (docs/web.md), as src/page/web_page.cpp
// writes it: a JSON header and one base64 block of binary arrays, some
// through meshoptimizer's codecs.
import { MeshoptDecoder } from "meshoptimizer/decoder";

// ---------------------------------------------------------------- the scene format
// The header's types are generated from the one schema, web/schema/page.schema.json
// (npm run types), which the browser test also validates every page against.
import type { ArrayRef, Lock } from "../generated/page_schema";
export type { ArrayRef, Look, PlannedPass, SceneHeader, StepMesh, Uniform } from "../generated/page_schema";

/// A camera of the page: its matrices (column-major 4x4) and look-at point.
export type Camera = Pick<Lock, "view" | "projection" | "target">;

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
