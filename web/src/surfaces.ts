// The page's surfaces on the GPU (docs/web.md), as IbfvsRenderer's data
// (src/render/renderer_data.cpp) holds them: the first step's mesh with
// every step's vectors and colours, a moving surface's points at this step
// and the next (and the pair the last frame drew), and the meshes of the
// steps whose triangles are their own (a changing mesh: the texture goes on
// from the image, no motion between meshes).
import { type ArrayRef, type SceneHeader, f32, i8, u16, u32, view } from "./format";

/// One mesh's vertex array and what drawing it takes.
interface Mesh {
  vao: WebGLVertexArrayObject;
  count: number; // indices
  cull: number; // closed_orientation: 0, or the side whose back faces hide
}

export class Surfaces {
  private readonly gl: WebGL2RenderingContext;
  private readonly scene: SceneHeader;
  private readonly meshes: Mesh[] = []; // [0]: the first step's; then meshes[] of the page
  private current = 0; // the mesh of this step
  private drawnMesh = 0; // the mesh the last frame drew
  private vectorBuffer: WebGLBuffer;
  private scalarBuffer: WebGLBuffer | null = null; // (colour, beta) per vertex, per step where they change
  private scalarSteps = 1;
  // A surface that moves (the scene's motion): every vertex's point and
  // normal at step 0, interleaved, and the moving vertices' in each stored set.
  // screws: each step's towards the next, per moving vertex (omega, lever).
  private motion: { base: Float32Array; moving: Uint32Array; points: Float32Array;
                    normals: Float32Array; screws: Float32Array; sets: number[] } | null = null;
  // This step's and the next's points and normals, and the screws between them.
  private surface: WebGLBuffer[] = [];
  private drawn: WebGLBuffer[] | null = null; // the pair the last frame drew, where setStep replaced it since
  private drawnMix = 0;

  constructor(gl: WebGL2RenderingContext, scene: SceneHeader, data: ArrayBuffer) {
    this.gl = gl;
    this.scene = scene;
    const s = scene, a = s.arrays;
    const points = (ref: ArrayRef) => {
      const q = view(data, ref, u16, 2), out = new Float32Array((q.length / 4) * 3);
      for (let i = 0; i < q.length; ++i) {
        const c = i % 4, lo = a.positions.min[c], hi = a.positions.max[c];
        if (c < 3) out[(i >> 2) * 3 + c] = lo + (hi - lo) * (q[i] / 65535);
      }
      return out;
    };
    const interleaved = (p: Float32Array, n: Int8Array) => {
      const out = new Float32Array((p.length / 3) * 6);
      for (let i = 0; i < p.length / 3; ++i)
        for (let c = 0; c < 3; ++c) {
          out[6 * i + c] = p[3 * i + c];
          out[6 * i + 3 + c] = Math.max(n[4 * i + c] / 127, -1);
        }
      return out;
    };

    // The first step's mesh: positions from 16 bits in the box, the rest as stored.
    const vao = gl.createVertexArray()!;
    gl.bindVertexArray(vao);
    const positions = points(a.positions), normals = view(data, a.normals, i8, 1);
    if (a.motion) {
      // Points and normals per step, as floats (setStep builds each step's).
      const q = view(data, a.motion.positions, u16, 2), n = view(data, a.motion.normals, i8, 1);
      const unit = new Float32Array((q.length / 4) * 3), at = new Float32Array((q.length / 4) * 3);
      for (let i = 0; i < q.length / 4; ++i)
        for (let c = 0; c < 3; ++c) {
          at[3 * i + c] = a.positions.min[c] + (a.positions.max[c] - a.positions.min[c]) * (q[4 * i + c] / 65535);
          unit[3 * i + c] = Math.max(n[4 * i + c] / 127, -1);
        }
      this.motion = { base: interleaved(positions, normals), moving: view(data, a.motion.moving, u32, 4),
                      points: at, normals: unit, screws: view(data, a.motion.screws, f32, 4),
                      sets: a.motion.sets };
    } else {
      this.attribute(0, positions, 3, gl.FLOAT, false);
      this.attribute(1, normals, 4, gl.BYTE, true);
    }
    // The field: attributes 2 and 4 read the current and the next time step
    // from one buffer (setStep moves them).
    this.vectorBuffer = this.attribute(2, view(data, a.vectors, u16, 2), 4, gl.HALF_FLOAT, false);
    gl.enableVertexAttribArray(4);
    if (a.scalars) {
      this.scalarBuffer = this.attribute(3, view(data, a.scalars, f32, 4), 2, gl.FLOAT, false);
      this.scalarSteps = a.scalars.steps ?? 1;
    } else {
      gl.vertexAttrib2f(3, 0, 0);
    }
    this.indices(view(data, a.indices, u32, 4));
    this.meshes.push({ vao, count: s.index_count, cull: s.cull });

    // The steps' own meshes: still, each with its step's vectors and colours.
    for (const m of a.meshes ?? []) {
      const own = gl.createVertexArray()!;
      gl.bindVertexArray(own);
      const p = points(m.positions), n = view(data, m.normals, i8, 1);
      if (this.motion) {
        // The looks read a moving surface: every point stands still here.
        const b = this.buffer(interleaved(p, n));
        this.pointSurface(0, 1, b);
        this.pointSurface(5, 6, b);
        this.pointSurface(7, -1, b);
        this.pointSurface(8, -1, b);
      } else {
        this.attribute(0, p, 3, gl.FLOAT, false);
        this.attribute(1, n, 4, gl.BYTE, true);
      }
      // Its one step's vectors at both field attributes (the buffer stays bound).
      this.attribute(2, view(data, m.vectors, u16, 2), 4, gl.HALF_FLOAT, false);
      gl.enableVertexAttribArray(4);
      gl.vertexAttribPointer(4, 4, gl.HALF_FLOAT, false, 0, 0);
      if (m.scalars) this.attribute(3, view(data, m.scalars, f32, 4), 2, gl.FLOAT, false);
      this.indices(view(data, m.indices, u32, 4));
      this.meshes.push({ vao: own, count: m.index_count, cull: m.cull });
    }
    gl.bindVertexArray(null);
  }

  private buffer(bytes: ArrayBufferView): WebGLBuffer {
    const gl = this.gl, b = gl.createBuffer()!;
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, bytes, gl.STATIC_DRAW);
    return b;
  }

  private attribute(location: number, bytes: ArrayBufferView, size: number, type: number,
                    normalized: boolean): WebGLBuffer {
    const gl = this.gl, b = this.buffer(bytes);
    gl.enableVertexAttribArray(location);
    gl.vertexAttribPointer(location, size, type, normalized, 0, 0);
    return b;
  }

  private indices(ids: Uint32Array): void {
    const gl = this.gl, b = gl.createBuffer()!;
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, b);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, ids, gl.STATIC_DRAW);
  }

  /// Attributes `point` and `normal` (or -1) at a buffer of interleaved points
  /// and normals; the vertex array bound.
  private pointSurface(point: number, normal: number, buffer: WebGLBuffer): void {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(point);
    gl.vertexAttribPointer(point, 3, gl.FLOAT, false, 24, 0);
    if (normal < 0) return;
    gl.enableVertexAttribArray(normal);
    gl.vertexAttribPointer(normal, 3, gl.FLOAT, false, 24, 12);
  }

  /// Every vertex's point and normal at step k, interleaved.
  private surfaceAt(k: number): Float32Array {
    const m = this.motion!, out = m.base.slice(), set = m.sets[k], count = m.moving.length;
    for (let j = 0; j < count; ++j) {
      const i = m.moving[j], from = 3 * (set * count + j);
      for (let c = 0; c < 3; ++c) {
        out[6 * i + c] = m.points[from + c];
        out[6 * i + 3 + c] = m.normals[from + c];
      }
    }
    return out;
  }

  /// Every vertex's screw from step k to the next (omega, lever interleaved:
  /// IbfvsRenderer's motion buffer); zeros, the chord, where `none`.
  private screwsAt(k: number, none: boolean): Float32Array {
    const m = this.motion!, out = new Float32Array(this.scene.vertex_count * 6), count = m.moving.length;
    if (none) return out;
    for (let j = 0; j < count; ++j) {
      const i = m.moving[j], from = 6 * (k * count + j);
      for (let c = 0; c < 6; ++c) out[6 * i + c] = m.screws[from + c];
    }
    return out;
  }

  /// Attributes `omega` and `lever` at a buffer of interleaved screws; the
  /// vertex array bound.
  private pointScrews(omega: number, lever: number, buffer: WebGLBuffer): void {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(omega);
    gl.vertexAttribPointer(omega, 3, gl.FLOAT, false, 24, 0);
    gl.enableVertexAttribArray(lever);
    gl.vertexAttribPointer(lever, 3, gl.FLOAT, false, 24, 12);
  }

  /// Step `step` and the next, as Session's StepPlayer puts them on the
  /// renderer: on the first step's mesh the field (and points) of this step
  /// and the next, or this one twice where the next has a mesh of its own;
  /// on a step's own mesh, that mesh. `drawnSince`: a frame was drawn since
  /// the last call (its surface then stays for the next frame's advection).
  setStep(step: number, drawnSince: boolean): void {
    const gl = this.gl, n = this.scene.steps, meshOf = (k: number) => this.scene.step_mesh?.[k] ?? 0;
    this.current = meshOf(step);
    if (this.current !== 0) return;
    const next = meshOf((step + 1) % n) === 0 ? (step + 1) % n : step;
    const bytes = this.scene.vertex_count * 8; // four half floats per vector
    gl.bindVertexArray(this.meshes[0].vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vectorBuffer);
    gl.vertexAttribPointer(2, 4, gl.HALF_FLOAT, false, 0, step * bytes);
    gl.vertexAttribPointer(4, 4, gl.HALF_FLOAT, false, 0, next * bytes);
    if (this.scalarSteps > 1) {
      // Each step's colours, as the session sets them at each step.
      gl.bindBuffer(gl.ARRAY_BUFFER, this.scalarBuffer);
      gl.vertexAttribPointer(3, 2, gl.FLOAT, false, 0, step * this.scene.vertex_count * 8);
    }
    if (this.motion) {
      // The pair the last frame drew stays for the next frame's advection,
      // where that frame drew this mesh.
      if (drawnSince && !this.drawn && this.drawnMesh === 0) this.drawn = this.surface;
      else this.surface.forEach((b) => gl.deleteBuffer(b));
      this.surface = [step, next].map((k) => this.buffer(this.surfaceAt(k)));
      this.surface.push(this.buffer(this.screwsAt(step, next === step)));
      this.pointSurface(0, 1, this.surface[0]);
      this.pointSurface(5, 6, this.surface[1]);
      this.pointScrews(9, 10, this.surface[2]);
    }
    gl.bindVertexArray(null);
  }

  /// Binds the mesh of this step for the IBFVS pass of `program` and says
  /// what to draw. `compensate`: the last frame's surface enters the
  /// advection (not locked, not the first frame, advecting in the last view).
  bind(compensate: boolean, fieldMix: number, drawnMix: WebGLUniformLocation | null): Mesh {
    const gl = this.gl, mesh = this.meshes[this.current];
    gl.bindVertexArray(mesh.vao);
    if (this.motion && this.current === 0) {
      const pair = compensate && this.drawn && this.drawnMesh === 0 ? this.drawn : this.surface;
      this.pointSurface(7, -1, pair[0]);
      this.pointSurface(8, -1, pair[1]);
      this.pointScrews(11, 12, pair[2]);
      gl.uniform1f(drawnMix, compensate && this.drawnMesh === 0 ? this.drawnMix : fieldMix);
    }
    return mesh;
  }

  /// After a frame that advanced the texture: its surface is the one the
  /// next frame's comes from.
  drawnFrame(fieldMix: number): void {
    if (this.drawn) this.drawn.forEach((b) => this.gl.deleteBuffer(b));
    this.drawn = null;
    this.drawnMix = fieldMix;
    this.drawnMesh = this.current;
  }
}
