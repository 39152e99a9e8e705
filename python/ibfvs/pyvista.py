"""ibfvs in PyVista: the animated flow texture as an actor of any plotter.

    import pyvista as pv
    import ibfvs.pyvista

    plotter = pv.Plotter()
    ibfvs.pyvista.add_flow(plotter, mesh, vectors="wallShearStress", scalars="p", cmap="coolwarm")
    plotter.show()                      # or screenshot(), open_movie() + write_frame(), ...

Each render of the plotter is one frame of the texture: a window animates it
on a timer; screenshots and movie frames each take the next frame. The
texture is drawn in the plotter's own OpenGL context with its camera, in
place of the actor's surface, coloured as `add_mesh` colours it (the same
keywords: scalars, cmap, clim, log_scale, the scalar bar), and depth-tested
against the plotter's other actors. `plotter.ibfvs.add_flow(mesh, ...)` (a
PyVista plotter component) and `mesh.ibfvs.add_flow(plotter, ...)` (a dataset
accessor) do the same; PyVista finds both through the package's entry
points, without an import.

It needs VTK's OpenGL 4.5 context, which Mesa (llvmpipe) and GPU drivers
give; the VTK is the one pip installs with PyVista (the package links no VTK
of its own). docs/python.md tells more.
"""

from __future__ import annotations

import math
import warnings

from . import _ibfvs, _options

if _ibfvs.has_vtk:
    # The build tree's module links ParaView's VTK: PyPI's vtk beside it
    # would be two VTKs in one process. Refused before pyvista loads it.
    raise ImportError("ibfvs.pyvista needs the pip package of ibfvs (pip install .), whose "
                      "module links no VTK; this one links ParaView's VTK (a CMake build tree)")

import numpy as np  # noqa: E402
import pyvista as pv  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkPolyDataMapper  # noqa: E402


__all__ = ["add_flow", "FlowLayer"]

# The scene keys that set the texture of a flow in a plotter: the plotter has
# the mesh, the camera, the size, the colours and the frames.
TEXTURE_KEYS = frozenset({
    "alpha", "beta", "scale", "step", "seed", "profile", "vg", "image_normalize", "filter",
    "contrast", "sharpen", "resample", "field_frame", "advect_view", "style", "noise_space",
    "spike_width", "inject", "init", "tangent", "reverse",
})
# add_mesh's own styles (its keyword `style`): the others are the texture's.
_MESH_STYLES = frozenset({"surface", "wireframe", "points", "points_gaussian"})


def _as_plotter(plotter):
    if not isinstance(plotter, pv.BasePlotter):
        raise TypeError(f"plotter must be a pyvista.Plotter, got {type(plotter).__name__}")
    if getattr(plotter, "_closed", False) or plotter.render_window is None:
        raise ValueError("the plotter is closed: make a new one")
    return plotter


def _surface(mesh):
    """The surface to draw: PolyData (a MultiBlock combined, a volume's outer surface)."""
    if not isinstance(mesh, pv.DataObject):
        try:
            mesh = pv.wrap(mesh)
        except Exception:  # noqa: BLE001 - pv.wrap raises several kinds
            mesh = None
        if mesh is None:
            raise TypeError("mesh must be a PyVista or VTK dataset")
    if isinstance(mesh, pv.MultiBlock):
        if mesh.n_blocks == 0:
            raise ValueError("mesh: the MultiBlock is empty")
        mesh = mesh.combine(merge_points=False)
    if not isinstance(mesh, pv.PolyData):
        mesh = mesh.extract_surface(algorithm="dataset_surface")
    if mesh.GetStrips() is not None and mesh.GetStrips().GetNumberOfCells() > 0:
        mesh = mesh.triangulate()  # triangle strips: their triangles (polygons stay as they are)
    if mesh.n_points == 0 or mesh.n_cells == 0:
        raise ValueError("mesh has no surface to draw (no points or no polygons)")
    if not np.all(np.isfinite(mesh.points)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(mesh.points), axis=1))[0])
        raise ValueError(f"mesh: point {bad} has a non-finite coordinate (NaN or infinity)")
    return mesh


def _triangles(surface, memory):
    """Triangles of the surface's polygons, split as every ibfvs reader splits
    them (the same cells in MEMORY: the triangles they had), and, per
    triangle, the cell it came from."""
    polys = surface.GetPolys()
    if polys is None or polys.GetNumberOfCells() == 0:
        raise ValueError("mesh has no polygons: the flow is drawn on surfaces")
    offsets = vtk_to_numpy(polys.GetOffsetsArray()).astype(np.int64, copy=False)
    ids = vtk_to_numpy(polys.GetConnectivityArray()).astype(np.int64, copy=False)
    tris, cell = _ibfvs.split_polygons(offsets, ids, np.asarray(surface.points, dtype=np.float64),
                                       memory)
    # Cells of the surface other than polygons (lines, vertices) come first in
    # VTK's cell order: the polygons' cell ids follow them.
    first = surface.n_cells - (len(offsets) - 1)
    return tris, cell + first


def _named_array(surface, name, what):
    """(values, 'point' or 'cell') of the surface's array `name`."""
    if name in surface.point_data:
        return np.asarray(surface.point_data[name]), "point"
    if name in surface.cell_data:
        return np.asarray(surface.cell_data[name]), "cell"
    names = sorted(set(surface.point_data.keys()) | set(surface.cell_data.keys()))
    raise ValueError(f"{what}: the mesh has no array named '{name}' "
                     f"(its arrays: {', '.join(names) if names else 'none'})")


def _vectors(surface, name):
    if name is None:
        name = surface.active_vectors_name
        if not name:
            raise ValueError("vectors: name the mesh's vector array (vectors='...'): it has no "
                             "active vectors")
    values, where = _named_array(surface, name, "vectors")
    components = 1 if values.ndim == 1 else values.shape[1]
    if values.ndim > 2 or components != 3:
        raise ValueError(f"vectors: the array '{name}' has {components} components; the flow "
                         "needs 3-component vectors")
    if values.dtype.kind not in "fiu":
        raise TypeError(f"vectors: the array '{name}' is not numeric ({values.dtype})")
    return name, values.astype(np.float64), where


def _vtk_matrix(m):
    return np.array([[m.GetElement(r, c) for c in range(4)] for r in range(4)])


_CLIENT_SIDE = ("ibfvs: the flow texture is drawn by the plotter's OpenGL, on the server; "
                "client-side rendering (vtk.js: trame's client mode, export_html) draws the "
                "plain surface. Render on the server (jupyter_backend='server', or trame's "
                "plotter_ui(plotter, mode='server', animate=True)), or use ibfvs.widget(...), "
                "the page's WebGL2 runtime")


class _FlowMapper(vtkPolyDataMapper):
    """VTK's polygon mapper (vtkOpenGLPolyDataMapper). A serializer for vtk.js
    asks it for its input (trame_vtk's mapper serializer): the texture cannot
    go there, and the user is told so, once a process."""

    told = False

    def GetInputDataObject(self, port, connection):  # noqa: N802 - VTK's name
        if not _FlowMapper.told:
            _FlowMapper.told = True
            warnings.warn(_CLIENT_SIDE, RuntimeWarning, stacklevel=2)
        return super().GetInputDataObject(port, connection)


class FlowLayer:
    """The texture of one actor: its surface, settings and the draw in the
    plotter's render. add_flow makes it; `actor.ibfvs` is this object."""

    def __init__(self, plotter, actor, vectors, settings, frames_per_step):
        self._plotter = plotter
        self._renderer = plotter.renderer  # the subplot add_mesh put the actor in
        self._actor = actor
        self._layer = _ibfvs.HostLayer()
        self._splits = _ibfvs.SplitMemory()  # the same cells, the same triangles at every update
        self._vectors = vectors
        self._colour_key = None
        self._problem = None
        self._tags = []
        self.topology = None  # add_flow(..., topology=True): the features drawn
        self._topology_drawn = None  # (options, actors) while they are drawn
        self._settings = {}
        self.set(**settings)
        if frames_per_step is not None:
            self._layer.set_frames_per_step(int(frames_per_step))
        # VTK's own polygon mapper: it calls back in its render, in the opaque
        # pass, where the texture is drawn instead of its surface.
        # add_mesh's pipeline stays its input: the scalars it made active.
        mapper = _FlowMapper()
        mapper.ShallowCopy(actor.GetMapper())
        mapper.SetInputConnection(actor.GetMapper().GetInputConnection(0, 0))
        mapper.Update()
        actor.SetMapper(mapper)
        self._mapper = mapper
        self._surface = pv.wrap(mapper.GetInput())
        _vectors(self._surface, vectors)
        # VTK's surface is discarded where the texture is drawn; not while a
        # hardware selector picks (the ids are VTK's own, of its surface).
        self._discarding = False
        self._tags = [mapper.AddObserver("StartEvent", self._start),
                      mapper.AddObserver("EndEvent", self._draw)]

    # ------------------------------------------------------------ settings

    def set(self, **settings):
        """Texture settings (the scene keys in TEXTURE_KEYS) on the running texture."""
        for key in settings:
            if key not in TEXTURE_KEYS:
                raise TypeError(f"'{key}' is not a texture setting of a flow in a plotter "
                                f"(those are: {', '.join(sorted(TEXTURE_KEYS))})")
        self._layer.set(_options(settings))
        self._settings.update(settings)

    @property
    def frame(self):
        """Texture frames since the texture last started afresh."""
        return self._layer.frame

    @property
    def problem(self):
        """Why the last render drew the plain surface (None: it drew the texture)."""
        return self._problem

    def update(self, mesh=None, vectors=None):
        """New data for the texture (a time step, moved points, another
        array): the texture goes on over it, moved points carrying it."""
        name = vectors or self._vectors
        if mesh is not None:
            surface = _surface(mesh).copy(deep=False)
            _vectors(surface, name)  # checked before anything changes
            # The array coloured by, as add_mesh made it active.
            drawn = pv.wrap(self._mapper.GetInput())
            for data, new in ((drawn.point_data, surface.point_data),
                              (drawn.cell_data, surface.cell_data)):
                active = data.active_scalars_name
                if active and active in new:
                    new.active_scalars_name = active
            self._mapper.SetInputData(surface)
            self._mapper.Update()
        self._vectors = name
        self._colour_key = None  # the arrays again at the next render
        if self._topology_drawn is not None:  # the new data's features, not the old
            self.show_topology(self._topology_drawn[0])

    def show_topology(self, options=None):
        """Draws the field's topology over the texture (add_flow's topology=):
        `options` ibfvs.topology's (feature_scale, min_strength, min_length),
        or None to take it away. Drawn again for new data (update)."""
        if self._topology_drawn is not None:
            for actor in self._topology_drawn[1]:
                self._plotter.remove_actor(actor, reset_camera=False, render=False)
            if getattr(self._plotter, "legend", None) is not None:
                self._plotter.remove_legend(render=False)
            self._topology_drawn, self.topology = None, None
        if options is None:
            return
        self.topology, actors = _add_topology(self._plotter, pv.wrap(self._mapper.GetInput()),
                                              self._vectors, self._settings, dict(options))
        self._topology_drawn = (dict(options), actors)

    # ------------------------------------------------------------ colours

    def _colour_values(self):
        """(values per point or per cell, 'point' or 'cell') of the array the
        mapper colours by, or (None, None) for the plain colour."""
        m = self._mapper
        lut = m.GetLookupTable()
        if not m.GetScalarVisibility() or lut is None:
            return None, None
        if m.GetColorMode() == 2:  # VTK_COLOR_MODE_DIRECT_SCALARS: no table to map through
            raise ValueError("colours given directly (rgb) are not drawn under the flow texture "
                             "yet; colour by a scalar array with a cmap")
        surface = self._surface
        # VTK's scalar modes: 0 the active point scalars, else the active
        # cell scalars; 1 and 2 the active point or cell scalars; 3 and 4 the
        # point or cell array by name.
        mode = m.GetScalarMode()
        point_name = surface.point_data.active_scalars_name
        cell_name = surface.cell_data.active_scalars_name
        if mode == 0:
            candidates = [("point", point_name), ("cell", cell_name)]
        elif mode == 1:
            candidates = [("point", point_name)]
        elif mode == 2:
            candidates = [("cell", cell_name)]
        elif mode in (3, 4):
            candidates = [("point" if mode == 3 else "cell", m.GetArrayName())]
        else:
            candidates = []
        for where, name in candidates:
            data = surface.cell_data if where == "cell" else surface.point_data
            if name and name in data:
                values = np.asarray(data[name], dtype=np.float64)
                if values.ndim == 2:
                    if lut.GetVectorMode() == 1:  # COMPONENT
                        c = min(max(lut.GetVectorComponent(), 0), values.shape[1] - 1)
                        values = values[:, c]
                    else:
                        values = np.linalg.norm(values, axis=1)
                return values, where
        return None, None

    def _table(self):
        """The mapper's colour table at 256 points over its range, its NaN
        colour, its range and whether it is logarithmic."""
        m = self._mapper
        lut = m.GetLookupTable()
        lo, hi = lut.GetRange() if m.GetUseLookupTableScalarRange() else m.GetScalarRange()
        log = bool(lut.UsingLogScale()) and lo > 0 and hi > 0
        if log:
            u = np.power(10.0, np.linspace(math.log10(lo), math.log10(hi), 256))
        else:
            u = np.linspace(lo, hi, 256)
        table = np.zeros((len(u), 3))
        rgb = [0.0, 0.0, 0.0]
        for i, x in enumerate(u):
            lut.GetColor(float(x), rgb)
            table[i] = rgb
        nan = tuple(lut.GetNanColor()[:3]) if hasattr(lut, "GetNanColor") else (0.5, 0.5, 0.5)
        return table, nan, lo, hi, log

    def _send_surface(self):
        """The surface, its vectors and colour positions to the texture:
        triangles apart where a cell array gives the vectors or colours
        (each triangle its cell's), shared points otherwise."""
        surface = self._surface
        _, flow, flow_at = _vectors(surface, self._vectors)
        colours, colour_at = self._colour_values()
        tris, cells = _triangles(surface, self._splits)
        points = np.asarray(surface.points, dtype=np.float64)
        apart = "cell" in (flow_at, colour_at)
        corner = tris.reshape(-1)  # the point of each corner, triangles apart
        if apart:
            points = points[corner]
            tris = np.arange(len(points), dtype=np.int64).reshape(-1, 3)
        per_vertex = (lambda v, at: (v[corner] if at == "point" else np.repeat(v[cells], 3, axis=0))
                      if apart else v)
        flow = per_vertex(flow, flow_at)
        t, table, nan = None, np.zeros((0, 3)), (0.5, 0.5, 0.5)
        if colours is not None:
            table, nan, lo, hi, log = self._table()
            t = np.asarray(_ibfvs.table_positions(colours.astype(np.float32), lo, hi, log),
                           dtype=np.float64)
            t = per_vertex(t, colour_at)
        self._layer.set_surface(points, tris, flow, t, "the mesh")
        self._layer.set_colours(table, nan)

    # ------------------------------------------------------------ the draw

    def _discard(self, on):
        if on == self._discarding:
            return
        shader = self._actor.GetShaderProperty()
        if on:
            shader.AddFragmentShaderReplacement(
                "//VTK::Color::Impl", True, "//VTK::Color::Impl\n  discard;  // ibfvs draws it", False)
        else:
            shader.ClearFragmentShaderReplacement("//VTK::Color::Impl", True)
        self._discarding = on

    def _start(self, mapper, event):
        """The mapper's StartEvent, before it builds its shader: VTK's
        surface discarded for the texture, kept for a hardware selector."""
        self._discard(self._renderer.GetSelector() is None)

    def _draw(self, mapper, event):
        """The mapper's EndEvent: VTK's context current, its framebuffer bound."""
        renderer = self._renderer
        if renderer.GetSelector() is not None:
            return  # picking: VTK's own ids, no texture
        window = renderer.GetRenderWindow()
        try:
            (w, h), (x0, y0) = renderer.GetSize(), renderer.GetOrigin()  # its viewport, pixels
            width, height = max(int(w), 1), max(int(h), 1)
            camera = renderer.GetActiveCamera()
            view = _vtk_matrix(camera.GetModelViewTransformMatrix()) @ _vtk_matrix(
                self._actor.GetMatrix())
            projection = _vtk_matrix(camera.GetProjectionTransformMatrix(width / height, -1, 1))
            self._surface = pv.wrap(self._mapper.GetInput())  # brought up to date by VTK
            key = self._content_key()
            if key != self._colour_key:
                self._send_surface()
                self._colour_key = key
            colour = self._actor.GetProperty().GetDiffuseColor()
            self._layer.render((int(x0), int(y0), width, height), view, projection,
                               camera.GetDistance(), colour)
            self._problem = None
        except Exception as e:  # noqa: BLE001 - shown once, the plain surface instead
            self._fail(str(e))
        finally:
            window.GetState().Reset()

    def _content_key(self):
        """What the texture takes from the surface and the mapper's colours:
        the same key, nothing to send. add_mesh's pipeline hands the mapper a
        new shallow copy at every render (its MTime moves): the arrays are the
        same objects, so they are compared by address and modification time."""
        def array(a):
            return None if a is None else (a.GetAddressAsString("vtkObject"), a.GetMTime())

        surface = self._surface
        data = []
        for fields in (surface.GetPointData(), surface.GetCellData()):
            for i in range(fields.GetNumberOfArrays()):
                data.append((fields.GetArrayName(i), array(fields.GetAbstractArray(i))))
            scalars = fields.GetScalars()
            data.append(scalars.GetName() if scalars is not None else None)
        points = surface.GetPoints()
        m = self._mapper
        lut = m.GetLookupTable()
        return (array(points.GetData()) if points is not None else None,
                array(surface.GetPolys()), tuple(data), m.GetScalarVisibility(), m.GetScalarMode(),
                m.GetArrayName(), m.GetColorMode(), tuple(m.GetScalarRange()),
                m.GetUseLookupTableScalarRange(), lut.GetMTime() if lut is not None else 0)

    def _fail(self, problem):
        """The plain surface from now on, and one warning that says why."""
        self._problem = problem
        self._discard(False)
        for tag in self._tags:
            self._mapper.RemoveObserver(tag)
        self._tags = []
        warnings.warn(f"ibfvs: {problem}; drawing the plain surface", RuntimeWarning, stacklevel=2)


def add_flow(plotter, mesh, vectors=None, *, frames_per_step=None, animate=True, topology=False,
             **keywords):
    """Adds `mesh` to `plotter` with the animated flow texture of its array
    `vectors` (3 components, point or cell data; default the active vectors)
    and returns the actor, as `plotter.add_mesh` does.

    Keywords that are texture settings (TEXTURE_KEYS: alpha, beta, scale,
    step, seed, style=crisp, ...) set the texture; every other keyword goes
    to `add_mesh` and colours the surface as it would (scalars, cmap, clim,
    log_scale, scalar_bar_args, show_scalar_bar, color, ...). frames_per_step:
    at least this many texture frames for each change of the data
    (FlowLayer.update), 3 by default. animate: a window re-renders on a
    timer (about 30 frames a second) while it is open. topology: True, or a
    dict of ibfvs.topology's options (feature_scale, min_strength,
    min_length), draws the field's critical points (spheres coloured by
    kind) and separation and attachment lines (red, blue) over the texture,
    with a legend; the features are `actor.ibfvs.topology` (a
    pyvista.PolyData), found again for each update's data.

    Raises ValueError naming the problem for a missing or non-vector
    array, a mesh without a surface, NaN points or a closed plotter, and
    TypeError for what is not a plotter, a mesh or a setting.
    """
    plotter = _as_plotter(plotter)
    surface = _surface(mesh)
    name, _, _ = _vectors(surface, vectors)
    settings, mesh_keywords = {}, {}
    for key, value in keywords.items():
        if key == "style" and str(value).lower() in _MESH_STYLES:
            mesh_keywords[key] = value
        elif key in TEXTURE_KEYS:
            settings[key] = value
        else:
            mesh_keywords[key] = value
    if mesh_keywords.get("opacity", 1.0) not in (1, 1.0, None):
        raise ValueError("opacity: the flow texture is drawn on opaque surfaces (opacity 1)")
    if mesh_keywords.get("rgb") or mesh_keywords.get("rgba"):
        raise ValueError("rgb: colours given directly are not drawn under the flow texture yet; "
                         "colour by a scalar array with a cmap")
    actor = plotter.add_mesh(surface, **mesh_keywords)
    layer = FlowLayer(plotter, actor, name, settings, frames_per_step)
    # The plotter keeps the layer as long as itself. Else the layer, its
    # mapper's Python wrapper and the observer's bound method are a cycle that
    # Python's collector finds unreachable once the caller drops the actor,
    # and clears while VTK still calls it: the surface vanished.
    if not hasattr(plotter, "_ibfvs_layers"):
        plotter._ibfvs_layers = []
    plotter._ibfvs_layers.append(layer)
    pv.set_new_attribute(actor, "ibfvs", layer)
    if topology:
        layer.show_topology(dict(topology) if isinstance(topology, dict) else {})
    if animate and not plotter.off_screen:
        _animate(plotter)
    return actor


def _add_topology(plotter, surface, vectors, settings, options):
    """The field's topology over the texture: lines and point glyphs in the
    kinds' colours, drawn a little in front of the surface they lie on."""
    from . import KIND_COLOURS, KINDS, topology

    keys = {k: v for k, v in settings.items() if k in ("reverse", "tangent")}
    found = topology(surface, vectors=vectors, **keys, **options)
    size = surface.length or 1.0
    kinds = found.cell_data["kind"]
    legend, actors = [], []
    for kind in sorted(set(int(k) for k in kinds)):
        part = found.extract_cells(np.flatnonzero(kinds == kind))
        colour = [c / 255.0 for c in KIND_COLOURS[kind]]
        if kind >= 10:
            actor = plotter.add_mesh(part, color=colour, line_width=3, reset_camera=False,
                                     lighting=False, pickable=False)
        else:
            glyphs = pv.PolyData(part.points).glyph(geom=pv.Sphere(radius=0.006 * size),
                                                    scale=False, orient=False)
            actor = plotter.add_mesh(glyphs, color=colour, reset_camera=False, pickable=False)
        # In front of the surface they lie on: VTK's coincident-topology
        # offset for lines and points, a little more for the glyphs.
        mapper = actor.GetMapper()
        mapper.SetResolveCoincidentTopologyToPolygonOffset()
        mapper.SetRelativeCoincidentTopologyLineOffsetParameters(0, -2000)
        mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(0, -2000)
        legend.append([KINDS[kind], colour])
        actors.append(actor)
    if legend:
        plotter.add_legend(legend, bcolor=None, face="rectangle", size=(0.22, 0.04 * len(legend)))
    return found, actors


def _animate(plotter):
    """A window renders about 30 times a second while it is open."""
    if getattr(plotter, "_ibfvs_timer", False):
        return
    plotter._ibfvs_timer = True

    def tick(*_):
        if not getattr(plotter, "_closed", True) and plotter.render_window is not None:
            plotter.render()

    iren = getattr(plotter, "iren", None)
    if iren is not None:
        iren.add_observer("TimerEvent", tick)
        iren.create_timer(33, repeating=True)


@pv.register_dataset_accessor("ibfvs", pv.DataObject)
class _Accessor:
    """mesh.ibfvs.add_flow(plotter, vectors=..., **keywords): add_flow for this mesh."""

    def __init__(self, mesh):
        self._mesh = mesh

    def add_flow(self, plotter, vectors=None, **keywords):
        return add_flow(plotter, self._mesh, vectors, **keywords)


if hasattr(pv, "register_plotter_component"):  # PyVista 0.48 and later

    @pv.register_plotter_component("ibfvs")
    class _Component:
        """plotter.ibfvs.add_flow(mesh, vectors=..., **keywords): add_flow
        in this plotter (in its active subplot, as add_mesh)."""

        def __init__(self, plotter):
            self._plotter = plotter

        def add_flow(self, mesh, vectors=None, **keywords):
            return add_flow(self._plotter, mesh, vectors, **keywords)

        @property
        def layers(self):
            """The flow layers of this plotter, in the order they were added."""
            return list(getattr(self._plotter, "_ibfvs_layers", ()))

        def __plotter_close__(self):
            # The layers' GL objects go with the plotter's context.
            self._plotter._ibfvs_layers = []
