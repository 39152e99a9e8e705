"""ibfvs: dense, animated, flow-aligned texture on curved surfaces.

Image Based Flow Visualization for Curved Surfaces (van Wijk, IEEE
Visualization 2003) on numpy arrays, VTK-style meshes and scene files,
rendered headless (EGL) on the GPU or Mesa's llvmpipe. docs/python.md has
worked examples.

    import ibfvs
    image = ibfvs.render(points, triangles, vectors, size=(512, 512), frames=150)

Options are the scene keys of `ibfvs render` (docs/scenes.md) with
underscores: alpha, beta, scale, step, tangent, background, seed, camera,
image_normalize, style, ... with the same defaults.
"""

from __future__ import annotations

import base64
import html
import os
import tempfile
from collections.abc import Mapping

import numpy as np

from . import _external, _ibfvs

__all__ = ["render", "Animation", "Video", "widget", "keys", "topology", "Topology", "KINDS", "KIND_COLOURS", "has_vtk", "__version__"]

__version__ = _ibfvs.__version__  # CMakeLists.txt's project(), the one version
has_vtk = _ibfvs.has_vtk
_external.install()  # netCDF through xarray where the build has no netCDF-C (the wheel)


def keys():
    """Every scene key as (name, help, default) with default a list of text forms."""
    return _ibfvs.keys()


_KEY_NAMES = {k[0] for k in _ibfvs.keys()}


def _text(key, value):
    """A Python value in the key's text form: True -> "true", (1, 2) -> "1,2"."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    if isinstance(value, (int, float, np.integer, np.floating)):
        return repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))
    if key == "size" and len(value) == 2:
        return f"{int(value[0])}x{int(value[1])}"
    try:
        return ",".join(_text(key, v) for v in value)
    except TypeError:
        raise TypeError(f"option {key}: cannot use a {type(value).__name__}") from None


def _options(options):
    """Options as (key, text) pairs; repeatable keys (element) take lists."""
    out = []
    for key, value in options.items():
        if key not in _KEY_NAMES:
            close = sorted(k for k in _KEY_NAMES if k[:3] == key[:3])
            raise TypeError(f"unknown option '{key}'" + (f" (did you mean {', '.join(close)}?)" if close else ""))
        if value is None:
            continue
        if key in ("element", "field_step", "scalar") and isinstance(value, (list, tuple)) and value and not isinstance(value[0], (int, float)):
            out.extend((key, _text(key, v)) for v in value)
        else:
            out.append((key, _text(key, value)))
    return out


def _check_index_array(triangles):
    a = np.asarray(triangles)
    if a.dtype.kind not in "iu":
        raise TypeError(f"triangles must be integers (int32 or int64), got {a.dtype}")
    return a


def _check_float_array(name, values):
    a = np.asarray(values)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must be numbers (float32, float64 or integers), got {a.dtype}")
    return a


def _faces_to_triangles(faces, points, memory=None):
    """A VTK-style cell array [n, i0, ..., n, ...] as triangles, each polygon
    split as every ibfvs reader splits it (the same cells in MEMORY: the
    triangles they had); per triangle, the index of the cell it came from;
    and the number of cells."""
    faces = np.asarray(faces)
    if faces.dtype.kind not in "iu" or faces.ndim != 1:
        raise TypeError("faces must be a flat integer array [n, i0, i1, ..., n, ...]")
    offsets, ids = _ibfvs.cells_of_faces(faces.astype(np.int64, copy=False))
    tris, cells = _ibfvs.split_polygons(offsets, ids, np.asarray(points, dtype=np.float64), memory)
    return tris, cells, len(offsets) - 1


def _mesh_arrays(mesh, memory=None):
    """points, triangles, point arrays and cell arrays (per triangle) of an
    object with `points`, a VTK-style `faces` and `point_data`/`cell_data`."""
    points = _check_float_array("points", mesh.points)
    triangles, cells, count = _faces_to_triangles(mesh.faces, points, memory)
    point_arrays = {str(k): np.asarray(v) for k, v in getattr(mesh, "point_data", {}).items()}
    cell_arrays = {}
    for k, v in getattr(mesh, "cell_data", {}).items():
        v = np.asarray(v)
        if v.dtype.kind in "fiu":
            cell_arrays[str(k)] = v[cells] if len(v) == count else v
    point_arrays = {k: v for k, v in point_arrays.items() if v.dtype.kind in "fiu"}
    return points, triangles, point_arrays, cell_arrays


def _put_vectors(vectors, points, triangles, point_arrays, cell_arrays):
    """vectors (n, 3) per point or (m, 3) per triangle as the array 'vectors'."""
    v = _check_float_array("vectors", vectors)
    n_points, n_tris = len(np.asarray(points)), len(np.asarray(triangles))
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vectors must have shape (n, 3), got {v.shape}")
    if len(v) == n_points:
        point_arrays["vectors"] = v
    elif len(v) == n_tris:
        cell_arrays["vectors"] = v
    else:
        raise ValueError(f"vectors has {len(v)} rows: expected one per point ({n_points}) "
                         f"or one per triangle ({n_tris})")


def _source(source, triangles, vectors, options, memory=None):
    """What Animation(source, triangles, vectors, **options) is given, as
    ("file", scene_file) with the mesh put in OPTIONS, or ("arrays", points,
    triangles, point_arrays, cell_arrays, name); OPTIONS gets the field."""
    point_arrays, cell_arrays = {}, {}
    name = "arrays"
    if source is None or isinstance(source, (str, os.PathLike)):
        if triangles is not None:
            raise TypeError("a file takes no triangles")
        path = "" if source is None else os.fspath(source)
        if isinstance(vectors, str):
            options.setdefault("field", "file:" + vectors)
        if path.endswith(".toml"):
            return ("file", path)
        if path:
            options["mesh"] = path
        return ("file", "")
    if hasattr(source, "points") and hasattr(source, "faces"):
        if triangles is not None:
            raise TypeError("a mesh object takes no separate triangles")
        points, triangles, point_arrays, cell_arrays = _mesh_arrays(source, memory)
        name = type(source).__name__
    else:
        points = _check_float_array("points", source)
        if triangles is None:
            raise TypeError("arrays need triangles: Animation(points, triangles, vectors)")
        triangles = _check_index_array(triangles)
    if isinstance(vectors, str):
        options.setdefault("field", "file:" + vectors)
    elif vectors is not None:
        _put_vectors(vectors, points, triangles, point_arrays, cell_arrays)
        options.setdefault("field", "file:vectors")
    return ("arrays", points, triangles, point_arrays, cell_arrays, name)


class Animation(_ibfvs.Animation):
    """An IBFVS animation in its own headless GL context.

    Animation(points, triangles, vectors, **options)   arrays
    Animation(mesh, vectors="U", **options)            a VTK-style mesh (PyVista's PolyData)
    Animation("wing.vtp", field="file:U", ...)         a mesh or dataset file
    Animation("scene.toml", **options)                 a scene file

    vectors: (n, 3) per point or (m, 3) per triangle, or the name of an array.
    """

    def __init__(self, source=None, triangles=None, vectors=None, **options):
        if "size" in options and isinstance(options["size"], (tuple, list)):
            options["size"] = tuple(options["size"])
        if hasattr(source, "points") and hasattr(source, "faces"):
            self._splits = _ibfvs.SplitMemory()  # its next states' cells split alike
        source_args = _source(source, triangles, vectors, options, getattr(self, "_splits", None))
        if source_args[0] == "file":
            super().__init__(source_args[1], _options(options))
            return
        _, points, triangles, point_arrays, cell_arrays, name = source_args
        super().__init__(points, triangles, point_arrays, cell_arrays, _options(options), name)
        self._data = (points, triangles, point_arrays, cell_arrays)

    def update(self, points=None, vectors=None, triangles=None, *, frames=0):
        """The next state of the data: a time step of your own loop, moved
        points, new vectors. The texture goes on from where it is, the
        points' motion carried into it (same triangles) or taken on from
        the image (other triangles); it never starts from noise again.

        points: (n, 3), or a VTK-style mesh (its points, faces and arrays);
        vectors: (n, 3) per point or (m, 3) per triangle; triangles: (m, 3)
        where they change. What is left out stays as it was (an animation
        made from a file needs points and triangles). frames: frames of the
        new state rendered now, the texture taking it on (0: the next step
        shows it)."""
        last = getattr(self, "_data", None)
        point_arrays, cell_arrays = {}, {}
        if points is not None and hasattr(points, "points") and hasattr(points, "faces"):
            if getattr(self, "_splits", None) is None:
                self._splits = _ibfvs.SplitMemory()
            points, triangles, point_arrays, cell_arrays = _mesh_arrays(points, self._splits)
        elif last is not None:
            point_arrays, cell_arrays = dict(last[2]), dict(last[3])
        if points is None or triangles is None:
            if last is None:
                raise TypeError("an animation made from a file needs points and triangles to update")
            points = last[0] if points is None else points
            triangles = last[1] if triangles is None else triangles
        points = _check_float_array("points", points)
        triangles = _check_index_array(triangles)
        if vectors is not None:
            point_arrays.pop("vectors", None)
            cell_arrays.pop("vectors", None)
            _put_vectors(vectors, points, triangles, point_arrays, cell_arrays)
        self._update(points, triangles, point_arrays, cell_arrays, int(frames))
        self._data = (points, triangles, point_arrays, cell_arrays)

    def set(self, **options):
        """Change settings on the running animation where they allow it (texture
        settings, step, scale, seed, tangent, camera, size: the session's rules,
        as the viewer's); others prepare the scene again, the texture going on over
        the same surface (another surface starts it afresh)."""
        self._set(_options(options))

    def frames(self, count, *, alpha=False):
        """Iterate over COUNT new frames, each a numpy image (copied)."""
        for _ in range(count):
            self.step()
            yield np.array(self.image(alpha))

    def __iter__(self):
        while True:
            self.step()
            yield np.array(self.image(False))

    # ---- Jupyter
    def _repr_png_(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "frame.png")
            self.save_png(path)
            with open(path, "rb") as f:
                return f.read()

    def to_html(self, path):
        """Write the scene as one self-contained web page that animates it in
        the browser with WebGL2 (docs/web.md): turn, zoom, pause, sliders."""
        if not str(path).lower().endswith((".html", ".htm")):
            raise ValueError(f"{path}: a page must be named NAME.html")
        with open(path, "wb") as f:
            f.write(self._page())

    def _repr_html_(self):
        """Jupyter: the live page inline (an iframe holding it), no server
        extension needed; None (the PNG instead) in a build without the
        browser runtime."""
        if not self._has_page():
            return None
        page = self._page().decode("utf-8")
        width, height = self.size
        return (f'<iframe srcdoc="{html.escape(page, quote=True)}" width="{max(width + 40, 480)}" '
                f'height="{height + 160}" style="border:0"></iframe>')

    def widget(self):
        """The live notebook widget of this animation (needs anywidget):
        the page's runtime in Jupyter, its settings synced both ways."""
        from .notebook import FlowWidget

        return FlowWidget(self)

    def write_video(self, path, frames, fps=30.0):
        """Render FRAMES more frames into a video file (.mp4, .webm, .mkv,
        .mov, .avi, .gif); the pip package's goes through imageio-ffmpeg's
        ffmpeg or one on PATH."""
        _external.find_ffmpeg()
        return super().write_video(os.fspath(path), frames, fps)

    def video(self, frames=90, fps=30.0):
        """The next FRAMES frames as an MP4 Video, shown in Jupyter as an
        HTML5 <video>."""
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "animation.mp4")
            self.write_video(path, frames, fps)
            with open(path, "rb") as f:
                return Video(f.read())


class Video:
    """An MP4 video in memory; Jupyter shows it as an HTML5 <video>."""

    def __init__(self, data: bytes):
        self.data = data

    def save(self, path):
        with open(path, "wb") as f:
            f.write(self.data)

    def _repr_html_(self):
        encoded = base64.b64encode(self.data).decode("ascii")
        return f'<video controls loop autoplay muted src="data:video/mp4;base64,{encoded}"></video>'


def widget(source=None, triangles=None, vectors=None, **options):
    """The live notebook widget (docs/python.md): an Animation, or the
    arguments that make one, shown by the web page's runtime in Jupyter.
    Its traits alpha, beta, step, scale, look, playing, ... follow the
    page's sliders and move them; `set(**keys)` takes any scene key.
    Needs anywidget (pip install 'ibfvs[notebook]')."""
    if isinstance(source, Animation):
        if triangles is not None or vectors is not None or options:
            raise TypeError("widget(animation) takes no other arguments; use animation.set(...)")
        return source.widget()
    return Animation(source, triangles, vectors, **options).widget()


def render(points, triangles=None, vectors=None, *, size=(512, 512), frames=150, alpha_channel=False, **options):
    """Render FRAMES frames and return the last as uint8 (H, W, 3), or
    (H, W, 4) with alpha_channel=True, rows top first.

    points, triangles, vectors as for Animation (arrays, a VTK-style mesh, or a
    file with vectors naming its array); options are the scene keys."""
    if frames < 1:
        raise ValueError("frames must be at least 1")
    anim = Animation(points, triangles, vectors, size=size, **options)
    anim.step(frames)
    return np.array(anim.image(alpha_channel))


#: Issue 64's `kind` values (critical points 1-6, lines 10-11): names, and
#: the colours every front end draws them in (sRGB 0-255).
KINDS = {kind: name for kind, name, _ in _ibfvs.topology_kinds()}
KIND_COLOURS = {kind: tuple(rgb) for kind, _, rgb in _ibfvs.topology_kinds()}


class Topology:
    """The skin-friction topology of a field (ibfvs.topology): numpy arrays.

    points (k, 3), normals (k, 3), kind (k,), index (k,), eigenvalues (k, 4):
    the critical points, the surface's normal there, their kind (KINDS),
    Poincare index and the Jacobian's eigenvalues (real and imaginary part of
    the first, then the second);
    lines: a list of dicts with kind (10 separation, 11 attachment), points
    (p, 3), normals (p, 3), magnitude (p,), eigenvalues (p, 2), closed,
    strength, length;
    index_sum, euler_characteristic, summary."""

    def __init__(self, found):
        self.points = found["points"]
        self.normals = found["normals"]
        self.kind = found["kind"]
        self.index = found["index"]
        self.eigenvalues = found["eigenvalues"]
        self.lines = list(found["lines"])
        self.index_sum = found["index_sum"]
        self.euler_characteristic = found["euler_characteristic"]
        self.degenerate_triangles = found["degenerate_triangles"]
        self.zero_triangles = found["zero_triangles"]
        self.summary = found["summary"]

    def __repr__(self):
        return f"<ibfvs.Topology {self.summary}>"

    def count(self, kind):
        """How many points or lines of KIND (a number or a name of KINDS)."""
        if isinstance(kind, str):
            kind = {v: k for k, v in KINDS.items()}[kind]
        if kind >= 10:
            return sum(1 for line in self.lines if line["kind"] == kind)
        return int(np.count_nonzero(self.kind == kind))

    def to_pyvista(self):
        """A pyvista.PolyData laid out as `ibfvs topology` writes its .vtp: a
        vertex per critical point, a polyline per line; cell arrays kind and
        strength, point arrays index, magnitude, eigenvalues and Normals."""
        import pyvista

        k = len(self.points)
        pts = [self.points.reshape(-1, 3)]
        normals = [self.normals.reshape(-1, 3)]
        index = [self.index.astype(np.int32)]
        magnitude = [np.zeros(k, np.float32)]
        eigen = [self.eigenvalues.reshape(-1, 4)]
        kind = [self.kind.astype(np.int32)]
        strength = [np.abs(self.eigenvalues[:, [0, 2]]).max(axis=1) if k else np.zeros(0)]
        verts = np.column_stack([np.ones(k, np.int64), np.arange(k)]).ravel()
        cells, start = [], k
        for line in self.lines:
            p = line["points"]
            ids = list(range(start, start + len(p))) + ([start] if line["closed"] else [])
            cells += [len(ids)] + ids
            start += len(p)
            pts.append(p)
            normals.append(line["normals"])
            index.append(np.zeros(len(p), np.int32))
            magnitude.append(line["magnitude"])
            e = np.zeros((len(p), 4))
            e[:, 0], e[:, 2] = line["eigenvalues"][:, 0], line["eigenvalues"][:, 1]
            eigen.append(e)
            kind.append(np.array([line["kind"]], np.int32))
            strength.append(np.array([line["strength"]]))
        mesh = pyvista.PolyData(np.concatenate(pts) if start else np.zeros((0, 3)))
        if k:
            mesh.verts = verts
        if self.lines:
            mesh.lines = np.array(cells, np.int64)
        mesh.point_data["index"] = np.concatenate(index)
        mesh.point_data["Normals"] = np.concatenate(normals).astype(np.float32)
        mesh.point_data["magnitude"] = np.concatenate(magnitude).astype(np.float32)
        mesh.point_data["eigenvalues"] = np.concatenate(eigen)
        mesh.cell_data["kind"] = np.concatenate(kind)
        mesh.cell_data["strength"] = np.concatenate(strength).astype(np.float64)
        mesh.field_data["summary"] = [self.summary]
        return mesh


def topology(source=None, triangles=None, vectors=None, *, min_strength=0.1, min_length=4.0, **options):
    """The skin-friction topology of a field on a surface: its critical points
    (zeros of the field, by the Jacobian's eigenvalues) and its separation and
    attachment lines (Kenwright, Henze and Levit's eigenvector method in its
    parallel-vectors form); docs/cfd.md.

    source, triangles, vectors and options as for Animation (arrays, a
    VTK-style mesh, a file or a scene; options the scene keys: field, blocks,
    reverse, time, ...). Returns a Topology of numpy arrays, or for a
    VTK-style mesh (PyVista's PolyData) a pyvista.PolyData as `ibfvs
    topology` writes it. min_strength: a line is kept where the flow
    converges onto it (or diverges) at least this fraction of the field's
    rate; min_length: lines at least this many edges long."""
    mesh_object = hasattr(source, "points") and hasattr(source, "faces")
    args = _source(source, triangles, vectors, options)
    if args[0] == "file":
        found = _ibfvs.topology(args[1], _options(options), float(min_strength), float(min_length))
    else:
        _, points, tris, point_arrays, cell_arrays, name = args
        found = _ibfvs.topology(points, tris, point_arrays, cell_arrays, _options(options), name,
                                float(min_strength), float(min_length))
    result = Topology(found)
    return result.to_pyvista() if mesh_object else result
