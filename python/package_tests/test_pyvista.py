"""ibfvs.pyvista.add_flow in a PyVista plotter, as a PyVista user draws:
the texture aligned with the true flow and animating from render to render,
coloured as add_mesh colours, hidden by nearer actors, on the surface and
only there, kept on the surface by a turning camera and carried by moving
points; one VTK in the process; bad input a Python exception."""

import colorsys
import math
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
import pyvista as pv
from PIL import Image

import ibfvs
import ibfvs.pyvista

SIZE = (320, 240)
SCALE = 1.2  # the parallel scale: the unit sphere fills 1/1.2 of the height


def swirl_sphere(res=96):
    """The unit sphere, its swirl about +Z and scalars to colour by."""
    s = pv.Sphere(radius=1.0, theta_resolution=res, phi_resolution=res)
    s.point_data["swirl"] = np.cross([0.0, 0.0, 1.0], s.points)
    s.point_data["height"] = s.points[:, 2]
    s.point_data["level"] = 1.0 + 99.0 * (s.points[:, 1] + 1.0) / 2.0  # 1..100, for log scale
    s.point_data["flat"] = np.stack([s.points[:, 0], s.points[:, 1]], axis=1)  # 2 components
    s.cell_data["band"] = s.cell_centers().points[:, 0]
    s.point_data["east"] = np.tile([1.0, 0.0, 0.0], (s.n_points, 1))  # on the surface: projected
    return s


def plotter(size=SIZE):
    p = pv.Plotter(off_screen=True, window_size=size)
    p.set_background("white")
    return p


def look_down_z(p):
    """The camera on +Z looking at the origin, Y up, parallel projection."""
    p.camera.position = (0.0, 0.0, 5.0)
    p.camera.focal_point = (0.0, 0.0, 0.0)
    p.camera.up = (0.0, 1.0, 0.0)
    p.enable_parallel_projection()
    p.camera.parallel_scale = SCALE


def start(p):
    p.show(auto_close=False)  # off screen: the first render
    return p


def frames(p, n):
    """N renders (each a texture frame), the last as an RGB picture."""
    for _ in range(n):
        p.render()
    return p.screenshot(return_img=True)[..., :3]


def radius_map(size=SIZE):
    """Per pixel: its distance from the image centre in world units, and
    the unit image direction of the swirl there (x right, y up)."""
    w, h = size
    px = np.arange(w) + 0.5 - w / 2.0
    py = h / 2.0 - (np.arange(h) + 0.5)
    x, y = np.meshgrid(px, py)
    per_unit = (h / 2.0) / SCALE
    r = np.hypot(x, y)
    d = np.stack([-y, x], axis=-1) / np.maximum(r, 1e-9)[..., None]
    return r / per_unit, d


def direction_png(path, size=SIZE):
    """The swirl's image direction as `ibfvs quality --direction` takes it
    (red, green 0.5 + 0.5 x, y; blue 255 where defined: off the silhouette
    and the pole)."""
    r, d = radius_map(size)
    ok = (r > 0.15) & (r < 0.85)
    rgb = np.zeros(r.shape + (3,), np.uint8)
    rgb[..., 0] = np.clip(np.round(127.5 + 127.5 * np.where(ok, d[..., 0], 0)), 0, 255)
    rgb[..., 1] = np.clip(np.round(127.5 + 127.5 * np.where(ok, d[..., 1], 0)), 0, 255)
    rgb[..., 2] = np.where(ok, 255, 0)
    Image.fromarray(rgb).save(path)
    return path


def ibfvs_command():
    exe = shutil.which("ibfvs", path=os.path.dirname(sys.executable))
    assert exe, "the console script ibfvs is not installed beside this Python"
    return exe


def alignment(picture, tmp_path, name="picture"):
    """A and W of `ibfvs quality` (the measure of the other picture tests)."""
    png = tmp_path / f"{name}.png"
    Image.fromarray(picture).save(png)
    done = subprocess.run([ibfvs_command(), "quality", "--png", str(png), "--direction",
                           str(direction_png(tmp_path / f"{name}-direction.png"))],
                          capture_output=True, text=True, check=True).stdout
    values = {}
    for line in done.splitlines():
        if "alignment A" in line:
            values["A"] = float(line.split()[2])
        if "streak width W" in line:
            values["W"] = float(line.split()[3])
    assert "A" in values, done
    return values


def hues(picture, mask):
    """Hue in degrees and saturation of the masked pixels."""
    rgb = picture[mask].astype(float) / 255.0
    hsv = np.array([colorsys.rgb_to_hsv(*c) for c in rgb])
    return hsv[:, 0] * 360.0, hsv[:, 1]


def hue_difference(a, b):
    d = np.abs(a - b) % 360.0
    return np.minimum(d, 360.0 - d)


def test_one_version_everywhere():
    from importlib.metadata import version

    out = subprocess.run([ibfvs_command(), "--version"], capture_output=True, text=True,
                         check=True).stdout
    assert ibfvs.__version__ == version("ibfvs") == out.split()[0]
    source = os.environ.get("IBFVS_SOURCE_DIR")
    if source:
        with open(os.path.join(source, "CMakeLists.txt")) as f:
            assert f"project(ibfvs VERSION {ibfvs.__version__}" in f.read()


def test_the_swirl_is_drawn_along_the_flow_and_animates(tmp_path):
    p = start(plotter())
    actor = ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", scalars="height",
                                   cmap="viridis", show_scalar_bar=False)
    look_down_z(p)
    a = frames(p, 40)
    b = frames(p, 1)
    assert actor.ibfvs.problem is None
    assert actor.ibfvs.frame >= 41  # one frame a render
    measured = alignment(a, tmp_path)
    assert measured["A"] > 0.9, measured  # random noise: about 0.5
    r, _ = radius_map()
    surface, outside = r < 0.9, r > 1.05
    change = np.abs(a.astype(int) - b.astype(int)).mean(axis=2)
    assert change[surface].mean() > 3.0, "the texture stood still from one render to the next"
    assert change[outside].max() == 0, "the background changed"
    assert (a[outside] == 255).all(), "texture off the surface"
    assert (a[surface] == 255).all(axis=1).mean() < 0.01, "background on the surface"


@pytest.mark.parametrize("keywords", [
    {"scalars": "height", "cmap": "coolwarm"},
    {"scalars": "height", "cmap": "viridis", "clim": (-0.2, 0.6)},
    {"scalars": "level", "cmap": "plasma", "log_scale": True},
    {"scalars": "band", "cmap": "turbo"},  # cell data
    {"color": "tomato"},
], ids=["point", "clim", "log", "cell", "colour"])
def test_colours_are_add_mesh_colours(keywords):
    """Hue where the surface is coloured, against add_mesh with the same
    keywords: the texture changes lightness, never the colour."""
    pictures = []
    for flow in (False, True):
        p = start(plotter())
        kw = dict(keywords, show_scalar_bar=False)
        if flow:
            ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", **kw)
        else:
            p.add_mesh(swirl_sphere(), **kw)
        look_down_z(p)
        pictures.append(frames(p, 30))
    r, _ = radius_map()
    mask = r < 0.8
    mesh_hue, mesh_sat = hues(pictures[0], mask)
    flow_hue, flow_sat = hues(pictures[1], mask)
    coloured = (mesh_sat > 0.25) & (flow_sat > 0.25)
    assert coloured.mean() > 0.3, "too few coloured pixels to compare"
    d = hue_difference(mesh_hue[coloured], flow_hue[coloured])
    assert np.median(d) < 4.0 and np.percentile(d, 90) < 12.0, (np.median(d),
                                                               np.percentile(d, 90))


def test_the_texture_outlives_the_actor_the_caller_dropped():
    """add_flow's actor not kept, and Python's collector run: the plotter
    still draws the texture (it keeps the layer)."""
    import gc

    p = start(plotter())
    ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl")
    look_down_z(p)
    gc.collect()
    a = frames(p, 5)
    r, _ = radius_map()
    assert (a[r < 0.9] == 255).all(axis=1).mean() < 0.01
    assert a[r < 0.9].mean(axis=1).std() > 10


def test_colours_changed_on_a_live_plotter_are_taken_the_surface_sent_once():
    """The colour map changed between renders reaches the texture; renders
    with nothing changed send the surface no more (add_mesh's pipeline hands
    the mapper a new copy each render: its arrays are the same)."""
    p = start(plotter())
    actor = ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", scalars="height",
                                   cmap="Reds", show_scalar_bar=False)
    look_down_z(p)
    sent = []
    layer = actor.ibfvs
    original = layer._send_surface
    layer._send_surface = lambda: (sent.append(1), original())
    red = frames(p, 10)
    assert len(sent) == 1
    actor.mapper.lookup_table.cmap = "Blues"
    blue = frames(p, 3)
    assert len(sent) == 2
    r, _ = radius_map()
    mask = r < 0.8
    before, after = red[mask].astype(int), blue[mask].astype(int)
    assert (before[:, 0] - before[:, 2]).mean() > 20  # reddish
    assert (after[:, 2] - after[:, 0]).mean() > 20  # bluish


def test_triangle_strips_are_drawn_whole():
    """A surface of triangle strips (vtkStripper's, PyVista's strip()) is
    drawn with its every triangle: no background on the sphere."""
    stripped = swirl_sphere().strip()
    assert stripped.GetStrips().GetNumberOfCells() > 0
    p = start(plotter())
    ibfvs.pyvista.add_flow(p, stripped, vectors="swirl")
    look_down_z(p)
    a = frames(p, 10)
    r, _ = radius_map()
    assert (a[r < 0.9] == 255).all(axis=1).mean() < 0.01


def test_polygons_split_as_the_readers_split_them_and_alike_when_they_move():
    """A PyVista mesh's polygons become the triangles every reader of ibfvs
    makes (an L is cut inside itself, not fanned across its notch), each
    with its cell, as numpy 2 holds them; the same cells moved keep their
    triangles (a moving mesh's steps)."""
    points = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0],
                       [3, 0, 0], [3, 1, 0]], dtype=float)
    faces = np.array([6, 2, 3, 4, 5, 0, 1, 4, 1, 6, 7, 2])  # the L from its notch, a square
    offsets, ids = ibfvs._ibfvs.cells_of_faces(faces)
    assert offsets.tolist() == [0, 6, 10] and ids.tolist() == [2, 3, 4, 5, 0, 1, 1, 6, 7, 2]
    memory = ibfvs._ibfvs.SplitMemory()
    tris, cells, count = ibfvs._faces_to_triangles(faces, points, memory)
    assert count == 2 and cells.tolist() == [0, 0, 0, 0, 1, 1]
    a, b, c = (points[tris[:, k]] for k in range(3))
    area = 0.5 * np.cross(b - a, c - a)[:, 2]
    assert (area > 0).all() and area[:4].sum() == pytest.approx(3.0)
    turned = points @ np.array([[0.6, 0.8, 0], [-0.8, 0.6, 0], [0, 0, 1.0]]) + 5.0
    again, _, _ = ibfvs._faces_to_triangles(faces, turned, memory)
    assert (again == tris).all() and memory.size == 1


def test_nearer_actors_hide_the_texture_and_the_scalar_bar_stays():
    p = start(plotter())
    ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", scalars="height")
    p.add_mesh(pv.Cube(center=(0.5, 0.0, 1.5), x_length=0.5, y_length=0.5, z_length=0.5),
               color="red", lighting=False)
    look_down_z(p)
    a = frames(p, 20)
    w, h = SIZE
    per_unit = (h / 2.0) / SCALE
    cx, cy = int(w / 2 + 0.5 * per_unit), int(h / 2)
    patch = a[cy - 5:cy + 5, cx - 5:cx + 5].reshape(-1, 3)
    assert (patch[:, 0] > 200).all() and (patch[:, 1] < 60).all() and (patch[:, 2] < 60).all()
    # The texture beside the cube, though the returned actor was dropped.
    left = a[cy - 20:cy + 20, int(w / 2 - 0.5 * per_unit) - 20:int(w / 2 - 0.5 * per_unit) + 20]
    assert (left == 255).all(axis=2).mean() < 0.01 and left.mean(axis=2).std() > 10
    # The scalar bar, drawn after the surfaces, is not covered by the texture:
    # where it is, the picture is add_mesh's.
    plain = []
    for bar in (True, False):
        q = start(plotter())
        q.add_mesh(swirl_sphere(), scalars="height", show_scalar_bar=bar)
        look_down_z(q)
        plain.append(frames(q, 1))
    bar = np.abs(plain[0].astype(int) - plain[1].astype(int)).max(axis=2) > 40
    assert bar.sum() > 500
    same = np.abs(plain[0][bar].astype(int) - a[bar].astype(int)).max(axis=1) < 40
    assert same.mean() > 0.95, same.mean()  # all but the text's edges over the sphere


def turned(picture, degrees):
    """The picture turned about its centre (counter-clockwise)."""
    return np.asarray(Image.fromarray(picture.astype(np.uint8)).rotate(degrees,
                                                                       resample=Image.BILINEAR))


def test_a_translucent_actor_in_front_blends_over_the_texture():
    """Drawn in the opaque pass with its depth, the texture is what VTK's
    translucent pass blends over: the red square in front tints it, and the
    streaks show through."""
    p = start(plotter())
    ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", show_scalar_bar=False)
    p.add_mesh(pv.Plane(center=(0.3, 0.0, 1.5), direction=(0, 0, 1), i_size=0.6, j_size=0.6),
               color="red", opacity=0.4)
    look_down_z(p)
    a = frames(p, 10).astype(float)
    w, h = SIZE
    per_unit = (h / 2.0) / SCALE
    cx, cy, half = int(w / 2 + 0.3 * per_unit), int(h / 2), int(0.2 * per_unit)
    under = a[cy - half:cy + half, cx - half:cx + half]
    beside = a[cy - half:cy + half, int(w / 2 - 0.5 * per_unit) - half:int(w / 2 - 0.5 * per_unit) + half]
    assert (under[..., 0] - under[..., 1]).mean() > (beside[..., 0] - beside[..., 1]).mean() + 30
    assert under.mean(axis=2).std() > 10  # the streaks through it


def test_a_turning_camera_keeps_the_texture_on_the_surface():
    """A roll of the camera about its axis turns the picture of the sphere:
    the texture (streaks along X) turns with it, on the surface, rather than
    standing in the image."""
    p = start(plotter(size=(240, 240)))
    ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="east", step=0.05)
    look_down_z(p)
    before = frames(p, 40).mean(axis=2)
    p.camera.roll += 30.0
    after = frames(p, 1).mean(axis=2)
    r, _ = radius_map((240, 240))
    mask = (r > 0.1) & (r < 0.7)
    on_surface = np.corrcoef(after[mask], turned(before, 30.0)[mask])[0, 1]
    in_image = np.corrcoef(after[mask], before[mask])[0, 1]
    assert on_surface > 0.6 and on_surface > in_image + 0.3, (on_surface, in_image)


def test_moving_points_carry_the_texture_from_step_to_step():
    """A time step that turns the sphere 30 degrees about the view axis, its
    vectors with it (FlowLayer.update, as a moving mesh's next step): the
    texture turns with the points."""
    sphere = swirl_sphere()
    p = start(plotter(size=(240, 240)))
    actor = ibfvs.pyvista.add_flow(p, sphere, vectors="east", step=0.05)
    look_down_z(p)
    before = frames(p, 40).mean(axis=2)
    moved = sphere.rotate_z(30.0, inplace=False)
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    moved.point_data["east"] = np.tile([c, s, 0.0], (moved.n_points, 1))
    actor.ibfvs.update(moved)
    after = frames(p, 1).mean(axis=2)
    r, _ = radius_map((240, 240))
    mask = (r > 0.1) & (r < 0.7)
    carried = np.corrcoef(after[mask], turned(before, 30.0)[mask])[0, 1]
    left = np.corrcoef(after[mask], before[mask])[0, 1]
    assert carried > 0.6 and carried > left + 0.3, (carried, left)


def test_a_movie_and_a_gif_take_one_texture_frame_a_picture(tmp_path):
    """open_movie and open_gif, with what the pyvista extra brings (imageio
    and imageio-ffmpeg): every frame in the file, each a texture frame on."""
    import imageio.v3 as iio

    for name, opener, rate in (("swirl.mp4", "open_movie", {"framerate": 10}),
                               ("swirl.gif", "open_gif", {"fps": 10})):
        p = plotter()
        actor = ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl")
        look_down_z(p)
        getattr(p, opener)(str(tmp_path / name), **rate)
        for _ in range(10):
            p.write_frame()
        p.close()
        assert actor.ibfvs.frame >= 10, name
        pictures = iio.imread(tmp_path / name, index=None)
        assert len(pictures) == 10, (name, len(pictures))
        r, _ = radius_map((pictures.shape[2], pictures.shape[1]))
        change = np.abs(pictures[-1].astype(int) - pictures[-2].astype(int))[..., :3].mean(axis=2)
        assert change[r < 0.9].mean() > 3.0, f"{name}: the texture stood still"


def test_settings_are_the_scene_keys_and_go_on_live():
    p = start(plotter())
    actor = ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl", alpha=0.2, scale=3.0,
                                   style="surface")
    look_down_z(p)
    frames(p, 5)
    actor.ibfvs.set(alpha=0.05, contrast=0.2)
    frames(p, 5)
    assert actor.ibfvs.frame >= 10  # the texture went on through the change
    with pytest.raises(ValueError, match="alpha"):
        actor.ibfvs.set(alpha=5.0)
    with pytest.raises(TypeError, match="not a texture setting"):
        actor.ibfvs.set(camera="iso")


def test_the_mesh_accessor_and_the_plotter_component_add_the_flow():
    p = start(plotter())
    actor = swirl_sphere().ibfvs.add_flow(p, vectors="swirl")
    other = p.ibfvs.add_flow(swirl_sphere().translate((3, 0, 0)), vectors="swirl")
    look_down_z(p)
    frames(p, 3)
    assert actor.ibfvs.frame >= 3 and actor.ibfvs.problem is None
    assert other.ibfvs.frame >= 3 and other.ibfvs.problem is None
    assert p.ibfvs.layers == [actor.ibfvs, other.ibfvs]


def test_pyvista_finds_the_plotter_component_and_the_accessor_by_their_entry_points():
    """In a fresh interpreter that never imports ibfvs: plotter.ibfvs and
    mesh.ibfvs come through the package's entry points (PyVista 0.48+)."""
    script = """
import sys
import numpy as np
import pyvista as pv
s = pv.Sphere(theta_resolution=48, phi_resolution=48)
s.point_data["swirl"] = np.cross([0.0, 0.0, 1.0], s.points)
p = pv.Plotter(off_screen=True, window_size=(96, 96))
assert "ibfvs" not in sys.modules
actor = p.ibfvs.add_flow(s, vectors="swirl", scalars="swirl")
other = s.copy().translate((3, 0, 0)).ibfvs.add_flow(p, vectors="swirl")
p.show(auto_close=False)
for _ in range(4):
    p.render()
assert [layer for layer in p.ibfvs.layers] == [actor.ibfvs, other.ibfvs]
print(actor.ibfvs.frame, other.ibfvs.frame, actor.ibfvs.problem, other.ibfvs.problem)
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          env={**os.environ, "VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow"})
    assert done.returncode == 0, done.stderr
    a, b, pa, pb = done.stdout.split()
    assert int(a) >= 4 and int(b) >= 4 and pa == pb == "None", done.stdout


def test_subplots_each_draw_their_own_flow_along_it(tmp_path):
    """Two viewports side by side, each with its flow: each aligned with
    its swirl (the right one turning the other way), animated, inside its
    own viewport."""
    p = pv.Plotter(off_screen=True, window_size=(2 * SIZE[0], SIZE[1]), shape=(1, 2))
    p.set_background("white")
    for column, sign in ((0, 1.0), (1, -1.0)):
        p.subplot(0, column)
        s = swirl_sphere()
        s.point_data["swirl"] = sign * s.point_data["swirl"]
        ibfvs.pyvista.add_flow(p, s, vectors="swirl", scalars="height", show_scalar_bar=False)
        look_down_z(p)
    p.show(auto_close=False)
    a = frames(p, 40)
    b = frames(p, 1)
    r, _ = radius_map()
    surface, outside = r < 0.9, r > 1.05
    outside[:, :2] = outside[:, -2:] = False  # PyVista's line between the subplots
    for column in (0, 1):
        half, next_half = (x[:, column * SIZE[0]:(column + 1) * SIZE[0]] for x in (a, b))
        measured = alignment(half, tmp_path, f"subplot{column}")
        assert measured["A"] > 0.9, (column, measured)  # the direction's sign does not count
        assert (half[outside] == 255).all(), f"texture off the sphere in subplot {column}"
        assert (half[surface] == 255).all(axis=1).mean() < 0.01, f"background on subplot {column}"
        change = np.abs(half.astype(int) - next_half.astype(int)).mean(axis=2)
        assert change[surface].mean() > 3.0, f"subplot {column} stood still"
    layers = p.ibfvs.layers
    assert len(layers) == 2 and all(layer.problem is None for layer in layers)


def test_picking_finds_the_flow_surface():
    """The texture is VTK's surface to every picker: the hardware selector
    (VTK's ids: the surface is not discarded while it picks) finds the actor
    and the cell under the cursor, the depth-buffer picker a point on the
    sphere, and the texture goes on after."""
    from vtkmodules.vtkCommonDataModel import vtkDataObject
    from vtkmodules.vtkRenderingCore import vtkHardwareSelector, vtkWorldPointPicker

    p = start(plotter())
    sphere = swirl_sphere()
    actor = ibfvs.pyvista.add_flow(p, sphere, vectors="swirl", scalars="height")
    look_down_z(p)
    before = frames(p, 10)
    w, h = SIZE
    per_unit = (h / 2.0) / SCALE
    x, y = int(w / 2 + 0.4 * per_unit), int(h / 2 + 0.3 * per_unit)  # display: y up
    selector = vtkHardwareSelector()
    selector.SetRenderer(p.renderer)
    selector.SetArea(x, y, x, y)
    selector.SetFieldAssociation(vtkDataObject.FIELD_ASSOCIATION_CELLS)
    selection = selector.Select()
    assert selection.GetNumberOfNodes() == 1
    node = selection.GetNode(0)
    assert node.GetProperties().Get(node.PROP()) is actor
    cell = int(node.GetSelectionList().GetValue(0))
    centre = sphere.cell_centers().points[cell]
    assert np.hypot(centre[0] - 0.4, centre[1] - 0.3) < 0.05 and centre[2] > 0, centre
    picker = vtkWorldPointPicker()
    picker.Pick(x, y, 0, p.renderer)
    point = np.array(picker.GetPickPosition())
    assert abs(np.linalg.norm(point) - 1.0) < 0.02 and abs(point[0] - 0.4) < 0.02, point
    assert p.renderer.PickProp(x, y) is not None
    assert p.renderer.PickProp(x, y).GetLastNode().GetViewProp() is actor
    after = frames(p, 2)
    r, _ = radius_map()
    assert actor.ibfvs.problem is None
    assert (after[r < 0.9] == 255).all(axis=1).mean() < 0.01, "the texture is gone after the pick"
    assert np.abs(after.astype(int) - before.astype(int))[r < 0.9].mean() > 3.0


def test_bad_input_raises_naming_the_problem():
    p = plotter()
    s = swirl_sphere()
    with pytest.raises(ValueError, match="no array named 'wind'.*swirl"):
        ibfvs.pyvista.add_flow(p, s, vectors="wind")
    with pytest.raises(ValueError, match="'flat' has 2 components"):
        ibfvs.pyvista.add_flow(p, s, vectors="flat")
    bad = s.copy()
    bad.points[7] = np.nan
    with pytest.raises(ValueError, match="point 7 has a non-finite coordinate"):
        ibfvs.pyvista.add_flow(p, bad, vectors="swirl")
    with pytest.raises(TypeError, match="pyvista.Plotter"):
        ibfvs.pyvista.add_flow("not a plotter", s, vectors="swirl")
    with pytest.raises(TypeError, match="mesh must be"):
        ibfvs.pyvista.add_flow(p, 42, vectors="swirl")
    with pytest.raises(ValueError, match="opacity"):
        ibfvs.pyvista.add_flow(p, s, vectors="swirl", opacity=0.5)
    with pytest.raises(ValueError, match="rgb"):  # never a picture in the wrong colours
        ibfvs.pyvista.add_flow(p, s, vectors="swirl", scalars="swirl", rgb=True)
    with pytest.raises(ValueError, match="alpha"):
        ibfvs.pyvista.add_flow(p, s, vectors="swirl", alpha=-1.0)
    p.close()
    with pytest.raises(ValueError, match="closed"):
        ibfvs.pyvista.add_flow(p, s, vectors="swirl")


def test_one_vtk_in_the_process():
    """ibfvs and pyvista side by side map one libvtkCommonCore: pip's."""
    p = start(plotter())
    ibfvs.pyvista.add_flow(p, swirl_sphere(), vectors="swirl")
    frames(p, 2)
    with open("/proc/self/maps") as f:
        paths = {line.split()[-1] for line in f if "libvtkCommonCore" in line}
    assert len(paths) == 1, paths
    import vtkmodules

    assert next(iter(paths)).startswith(os.path.dirname(vtkmodules.__file__)), paths
    assert not any("paraview" in path for path in paths)


def test_a_pvd_series_read_by_pyvista_plays_into_a_movie_carrying_the_texture(tmp_path):
    """A .pvd of a sphere turning 10 degrees a step (written as VTK's XML
    files), read by PyVista's own reader and played step by step into a
    movie: each step goes on from the last, its moved points carrying the
    texture (after three steps it has turned 30 degrees with them)."""
    pytest.importorskip("imageio")
    sphere = swirl_sphere()
    entries = []
    for k in range(4):
        step = sphere.rotate_z(10.0 * k, inplace=False)
        a = math.radians(10.0 * k)
        step.point_data["east"] = np.tile([math.cos(a), math.sin(a), 0.0], (step.n_points, 1))
        step.save(tmp_path / f"sphere_{k}.vtp")
        entries.append(f'<DataSet timestep="{k}" part="0" file="sphere_{k}.vtp"/>')
    (tmp_path / "sphere.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n' +
        "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    reader = pv.get_reader(str(tmp_path / "sphere.pvd"))
    assert list(reader.time_values) == [0.0, 1.0, 2.0, 3.0]
    reader.set_active_time_value(0.0)
    p = start(plotter(size=(240, 240)))
    actor = ibfvs.pyvista.add_flow(p, reader.read(), vectors="east", step=0.05,
                                   frames_per_step=1)
    look_down_z(p)
    before = frames(p, 40).mean(axis=2)
    p.open_movie(str(tmp_path / "series.mp4"), framerate=4)
    for t in reader.time_values[1:]:
        reader.set_active_time_value(t)
        actor.ibfvs.update(reader.read())
        p.write_frame()
    after = p.screenshot(return_img=True)[..., :3].mean(axis=2)
    p.close()
    assert (tmp_path / "series.mp4").stat().st_size > 1000
    r, _ = radius_map((240, 240))
    mask = (r > 0.1) & (r < 0.7)
    carried = np.corrcoef(after[mask], turned(before, 30.0)[mask])[0, 1]
    left = np.corrcoef(after[mask], before[mask])[0, 1]
    assert carried > 0.5 and carried > left + 0.3, (carried, left)


WINDOW = """
import time, numpy as np, pyvista as pv, ibfvs.pyvista
s = pv.Sphere(radius=1.0, theta_resolution=80, phi_resolution=80)
s["swirl"] = np.cross([0, 0, 1.0], s.points)
p = pv.Plotter(window_size=(320, 240))
a = ibfvs.pyvista.add_flow(p, s, vectors="swirl", scalars=s.points[:, 2])
p.show(interactive_update=True, auto_close=False)
start = time.time()
while time.time() - start < 2.0:
    p.update(1)                      # the window's events: its timer renders
print(type(p.render_window).__name__, a.ibfvs.frame, a.ibfvs.problem)
p.close()
"""


def test_a_window_animates_by_itself_under_x():
    """A plotter with a window (VTK's GLX window, under Xvfb): add_flow's
    timer renders on its own, about 30 frames a second, with the texture."""
    xvfb = shutil.which("xvfb-run")
    assert xvfb, "xvfb-run (Debian's xvfb) is missing"
    env = {k: v for k, v in os.environ.items() if k != "VTK_DEFAULT_OPENGL_WINDOW"}
    done = subprocess.run([xvfb, "-a", "-s", "-noreset -screen 0 1024x768x24", sys.executable,
                           "-c", WINDOW], capture_output=True, text=True, timeout=120, env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    window, frames, problem = done.stdout.split()[-3:]
    assert window == "vtkXOpenGLRenderWindow"
    assert int(frames) >= 20 and problem == "None", done.stdout


def spiral_sphere(res=96, pull=1.0):
    """The unit sphere, turning about +Z and pulled onto its equator (a closed
    separation line; pull < 0: an attachment line), spiralling out of the
    poles."""
    s = pv.Sphere(radius=1.0, theta_resolution=res, phi_resolution=res)
    p = s.points / np.linalg.norm(s.points, axis=1)[:, None]
    z = p[:, 2:3]
    s.point_data["spiral"] = np.cross([0.0, 0.0, 1.0], p) - pull * z * (np.array([0, 0, 1.0]) - z * p)
    return s


def test_topology_gives_the_separation_line_and_the_foci_as_polydata():
    found = ibfvs.topology(spiral_sphere(), vectors="spiral")
    assert isinstance(found, pv.PolyData)
    kind = found.cell_data["kind"]
    assert sorted(kind.tolist()) == [5, 5, 10], found.field_data["summary"]  # two foci, a line
    assert found.n_verts == 2 and found.n_lines == 1
    line = found.extract_cells(np.flatnonzero(kind == 10))
    assert np.abs(line.points[:, 2]).max() < 0.02  # on the equator (edges about 0.065)
    assert found.point_data["index"].sum() == 2  # Poincare-Hopf: the sphere's 2
    assert "index sum 2 (Euler characteristic 2)" in found.field_data["summary"][0]
    # Its colours as every front end draws them (rgb=True shows them as they
    # are), its ids, and how each line was found.
    assert [tuple(c) for c in found.cell_data["colour"].tolist()] == [
        ibfvs.KIND_COLOURS[k] for k in kind.tolist()]
    assert sorted(found.cell_data["id"].tolist()) == [0, 1, 2]
    assert found.cell_data["origin"][kind == 10].tolist() == [2]  # a closed orbit
    reverse = ibfvs.topology(spiral_sphere(pull=-1.0), vectors="spiral")
    assert sorted(reverse.cell_data["kind"].tolist()) == [4, 4, 11]
    arrays = ibfvs.topology(*_arrays_of(spiral_sphere()))
    assert isinstance(arrays, ibfvs.Topology)
    assert arrays.count("separation line") == 1 and arrays.lines[0]["closed"]


def _arrays_of(s):
    return s.points, s.regular_faces, s.point_data["spiral"]


def test_the_command_writes_a_vtp_that_vtk_reads(tmp_path):
    out = tmp_path / "torus.vtp"
    done = subprocess.run([ibfvs_command(), "topology", "torus", "--field", "gradient:down:1,0,0.137",
                           "-o", str(out)], capture_output=True, text=True, check=True).stdout
    assert "4 critical points (2 saddles, 1 attracting node, 1 repelling node)" in done
    read = pv.read(out)
    assert read.n_verts == 4
    kinds = read.cell_data["kind"].tolist()
    assert sorted(kinds[:4]) == [1, 1, 2, 3] and set(kinds[4:]) <= {10, 11}
    assert read.point_data["eigenvalues"].shape == (read.n_points, 4)
    assert read.point_data["index"].sum() == 0


def test_add_flow_draws_the_topology_over_the_texture():
    p = start(plotter())
    actor = ibfvs.pyvista.add_flow(p, spiral_sphere(), vectors="spiral", topology=True)
    # From the side: the equator, a separation line, across the middle.
    p.camera.position = (5.0, 0.0, 0.0)
    p.camera.focal_point = (0.0, 0.0, 0.0)
    p.camera.up = (0.0, 0.0, 1.0)
    p.enable_parallel_projection()
    p.camera.parallel_scale = SCALE
    picture = frames(p, 20)
    assert actor.ibfvs.problem is None
    assert sorted(actor.ibfvs.topology.cell_data["kind"].tolist()) == [5, 5, 10]
    red = (picture[..., 0] > 170) & (picture[..., 1] < 90) & (picture[..., 2] < 90)
    w, h = SIZE
    per_unit = (h / 2.0) / SCALE
    rows = np.flatnonzero(red.any(axis=1))
    middle = h / 2.0
    # The line lies along the middle row, in front of the texture...
    band = red[int(middle - 4):int(middle + 4), :]
    columns = np.arange(w) + 0.5 - w / 2.0
    across = np.abs(columns) < 0.8 * per_unit
    assert band.any(axis=0)[across].mean() > 0.9, "the separation line is not drawn across"
    # ...and nowhere else but the legend's swatch (the top right corner).
    body = red[:, : int(0.7 * w)]
    far = np.abs(np.flatnonzero(body.any(axis=1)) + 0.5 - middle)
    assert far.max() < 6, f"red off the equator: rows {rows}"
    # The texture still moves around it.
    again = frames(p, 1)
    off_line = np.abs(np.arange(h) + 0.5 - middle)[:, None] > 10
    surface = (np.hypot(columns[None, :], (middle - np.arange(h) - 0.5)[:, None]) < 0.8 * per_unit)
    change = np.abs(picture.astype(int) - again.astype(int)).mean(axis=2)
    assert change[surface & off_line].mean() > 3.0
    # New data (the flow reversed: an attachment line, attracting foci): its
    # own features, drawn instead of the old.
    actor.ibfvs.update(spiral_sphere(pull=-1.0))
    picture = frames(p, 3)
    assert sorted(actor.ibfvs.topology.cell_data["kind"].tolist()) == [4, 4, 11]
    red = (picture[..., 0] > 170) & (picture[..., 1] < 90) & (picture[..., 2] < 90)
    blue = (picture[..., 2] > 170) & (picture[..., 0] < 90) & (picture[..., 1] < 140)
    assert not red[:, : int(0.7 * w)].any(), "the old separation line is still drawn"
    assert blue[int(middle - 4):int(middle + 4), :].any(axis=0)[across].mean() > 0.9
