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

__all__ = ["render", "Animation", "Video", "widget", "keys", "topology", "Topology", "KINDS", "KIND_COLOURS", "ORIGINS", "has_vtk", "__version__"]

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
    """The skin-friction topology of a field at one step (ibfvs.topology):
    numpy arrays laid out as `ibfvs topology` writes its .vtp (one layout
    for the command, ParaView and this module).

    The critical points: points (k, 3), normals (k, 3), kind (k,), index
    (k,), eigenvalues (k, 4) (real and imaginary part of the first, then
    the second), strength (k,) (the largest absolute real part), id (k,);
    lines: a list of dicts with kind (10 separation, 11 attachment), id,
    origin (ORIGINS), points (p, 3), normals (p, 3), magnitude (p,),
    eigenvalues (p, 2), closed, strength, length; index_sum,
    euler_characteristic, summary; layout: the arrays as laid out (points,
    cells and the cell and point arrays of the .vtp)."""

    def __init__(self, layout):
        self.layout = layout
        verts = np.asarray(layout["vert_connectivity"], dtype=np.int64)
        k = len(verts)
        points = np.asarray(layout["points"], dtype=np.float64).reshape(-1, 3)
        normals = np.asarray(layout["normals"], dtype=np.float64).reshape(-1, 3)
        eigen = np.asarray(layout["eigenvalues"]).reshape(-1, 4)
        self.points = points[verts]
        self.normals = normals[verts]
        self.kind = np.asarray(layout["kind"][:k])
        self.id = np.asarray(layout["id"][:k])
        self.index = np.asarray(layout["index"])[verts]
        self.eigenvalues = eigen[verts]
        self.strength = np.asarray(layout["strength"][:k])
        self.lines = []
        conn = np.asarray(layout["line_connectivity"], dtype=np.int64)
        start = 0
        for i, end in enumerate(np.asarray(layout["line_offsets"], dtype=np.int64)):
            closed = bool(layout["closed"][i])
            ids = conn[start:end][:-1] if closed else conn[start:end]
            start = end
            self.lines.append({
                "kind": int(layout["kind"][k + i]), "id": int(layout["id"][k + i]),
                "origin": int(layout["origin"][k + i]),
                "points": points[ids], "normals": normals[ids],
                "magnitude": np.asarray(layout["magnitude"])[ids],
                "eigenvalues": eigen[ids][:, [0, 2]], "closed": closed,
                "strength": float(layout["strength"][k + i]), "length": float(layout["length"][k + i]),
            })
        self.index_sum = layout["index_sum"]
        self.euler_characteristic = layout["euler_characteristic"]
        self.degenerate_triangles = layout["degenerate_triangles"]
        self.zero_triangles = layout["zero_triangles"]
        self.cancelled = layout["cancelled"]
        self.on_lines = layout["on_lines"]
        self.scale = layout["scale"]
        self.summary = layout["summary"]

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
        vertex per critical point, a polyline per line; cell arrays kind, id,
        strength, length, origin and colour (the kinds' sRGB: drawn as they
        are with rgb=True), point arrays index, magnitude, eigenvalues and
        Normals; field data summary."""
        import pyvista

        g = self.layout
        mesh = pyvista.PolyData(np.asarray(g["points"], dtype=np.float32).reshape(-1, 3))

        def cells(offsets, connectivity):
            offsets = np.concatenate([[0], np.asarray(offsets, dtype=np.int64)])
            return np.insert(np.asarray(connectivity, dtype=np.int64), offsets[:-1], np.diff(offsets))

        if len(g["vert_offsets"]):
            mesh.verts = cells(g["vert_offsets"], g["vert_connectivity"])
        if len(g["line_offsets"]):
            mesh.lines = cells(g["line_offsets"], g["line_connectivity"])
        for name in ("index", "magnitude", "eigenvalues"):
            mesh.point_data[name] = np.asarray(g[name])
        mesh.point_data["Normals"] = np.asarray(g["normals"], dtype=np.float32)
        for name in ("kind", "id", "strength", "length", "origin", "colour"):
            mesh.cell_data[name] = np.asarray(g[name])
        mesh.field_data["summary"] = [self.summary]
        return mesh


#: The `origin` of a line (how it was found): 1 from a saddle (a
#: separatrix), 2 a closed orbit, 3 open (from no saddle), 4 a line of zeros.
ORIGINS = {1: "separatrix", 2: "closed orbit", 3: "open", 4: "zeros"}

_TOPOLOGY_DEFAULTS = _ibfvs.topology_defaults()


def topology(source=None, triangles=None, vectors=None, *, feature_scale=_TOPOLOGY_DEFAULTS[0],
             min_strength=_TOPOLOGY_DEFAULTS[1], min_length=_TOPOLOGY_DEFAULTS[2], **options):
    """The skin-friction topology of a field on a surface: its critical points
    and its separation and attachment lines, found by following the field
    (docs/cfd.md).

    source, triangles, vectors and options as for Animation (arrays, a
    VTK-style mesh, a file or a scene; options the scene keys: field,
    blocks, reverse, time, ...). Returns a Topology of numpy arrays, or for
    a PyVista mesh a pyvista.PolyData as `ibfvs topology` writes it; for a
    series (several time steps) a list of them, one a step, each feature
    keeping its id from step to step. feature_scale: the significance
    scale, a fraction of the surface's size (a saddle and a node closer
    cancel; lines are measured in it); min_strength: a line is kept where its
    neighbours converge onto it (or diverge) by e^min_strength at least;
    min_length: lines at least this many scales long. Vectors that are not
    finite are set to zero with a RuntimeWarning (what Animation's
    `warnings` lists)."""
    import warnings as _warnings

    # A PyVista mesh (not one of its arrays, which are numpy arrays of its module).
    pyvista_mesh = type(source).__module__.split(".")[0] == "pyvista" and hasattr(source, "n_cells")
    args = _source(source, triangles, vectors, options)
    limits = (float(feature_scale), float(min_strength), float(min_length))
    if args[0] == "file":
        found = _ibfvs.topology(args[1], _options(options), *limits)
    else:
        _, points, tris, point_arrays, cell_arrays, name = args
        found = _ibfvs.topology(points, tris, point_arrays, cell_arrays, _options(options), name, *limits)
    for problem in found["warnings"]:
        _warnings.warn(f"ibfvs: {problem}", RuntimeWarning, stacklevel=2)
    steps = [Topology(step) for step in found["steps"]]
    if pyvista_mesh:
        steps = [step.to_pyvista() for step in steps]
    return steps[0] if len(steps) == 1 else steps

