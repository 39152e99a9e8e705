"""The Python module as a user scripts it: arrays in every dtype and order,
VTK-style meshes, files, live settings, numpy out, errors that are Python
exceptions (never a dead interpreter), and the same pictures as the command."""

import os
import subprocess
import threading

import numpy as np
import pytest

import ibfvs

SIZE = (64, 64)


def torus(n_major=48, n_minor=16, R=1.0, r=0.35):
    """A torus around +Y: points (n, 3), triangles (m, 3), a rotation about +Y."""
    u = np.linspace(0, 2 * np.pi, n_major, endpoint=False)
    v = np.linspace(0, 2 * np.pi, n_minor, endpoint=False)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    x = (R + r * np.cos(vv)) * np.cos(uu)
    z = (R + r * np.cos(vv)) * np.sin(uu)
    y = r * np.sin(vv)
    points = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    tris = []
    for i in range(n_major):
        for j in range(n_minor):
            a = i * n_minor + j
            b = ((i + 1) % n_major) * n_minor + j
            c = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
            d = i * n_minor + (j + 1) % n_minor
            tris += [(a, b, c), (a, c, d)]
    triangles = np.array(tris, dtype=np.int64)
    vectors = np.cross([0.0, 1.0, 0.0], points)  # rotation about +Y
    return points, triangles, vectors


def test_render_returns_an_image_with_texture_on_the_surface_only():
    p, t, v = torus()
    image = ibfvs.render(p, t, v, size=SIZE, frames=20, camera=(0, 30, 0))
    assert image.shape == (64, 64, 3) and image.dtype == np.uint8
    # The corners are background (grey 0.5); the middle row crosses the torus
    # and carries noise.
    assert (image[0, 0] == 128).all() and (image[-1, -1] == 128).all()
    row = image[32].astype(float)
    assert row.std() > 10
    rgba = ibfvs.render(p, t, v, size=SIZE, frames=2, alpha_channel=True)
    assert rgba.shape == (64, 64, 4)


def test_dtypes_and_orders_give_the_same_picture():
    p, t, v = torus()
    ref = ibfvs.render(p, t, v, size=SIZE, frames=10)
    same = [
        ibfvs.render(p.astype(np.float32), t.astype(np.int32), v.astype(np.float32), size=SIZE, frames=10),
        ibfvs.render(np.asfortranarray(p), np.asfortranarray(t), np.asfortranarray(v), size=SIZE, frames=10),
        ibfvs.render(p.tolist(), t.tolist(), v.tolist(), size=SIZE, frames=10),
    ]
    for other in same:
        assert np.abs(other.astype(int) - ref.astype(int)).max() <= 1


def test_vectors_per_triangle_and_by_name():
    p, t, v = torus()
    per_triangle = v[t].mean(axis=1)
    a = ibfvs.render(p, t, per_triangle, size=SIZE, frames=5)
    assert a.std() > 5


class PolyLike:
    """What PyVista's PolyData offers: points, a VTK cell array, data mappings."""

    def __init__(self, points, triangles, point_data, cell_data=None):
        self.points = points
        self.faces = np.hstack([np.full((len(triangles), 1), 3), triangles]).ravel()
        self.point_data = point_data
        self.cell_data = cell_data or {}


def test_duck_typed_mesh_with_named_arrays():
    p, t, v = torus()
    mesh = PolyLike(p, t, {"U": v, "height": p[:, 1]})
    anim = ibfvs.Animation(mesh, vectors="U", size=SIZE, color_by="height")
    anim.step(5)
    assert anim.image().shape == (64, 64, 4)
    # Quads in the cell array are fanned into triangles.
    quads = PolyLike(p, t[:, :3], {"U": v})
    quads.faces = np.hstack([[4, 0, 1, 2, 3], quads.faces])
    ibfvs.Animation(quads, vectors="U", size=SIZE).step(1)


def test_the_same_frames_as_the_command(tmp_path):
    exe = os.environ.get("IBFVS_EXE")
    if not exe:
        pytest.skip("IBFVS_EXE not set")
    args = ["--mesh", "torus", "--field", "rotate:0,1,0", "--frames", "12", "--size", "64x48"]
    subprocess.run([exe, "render", *args, "--out", str(tmp_path / "cli.png"), "-q"], check=True)
    anim = ibfvs.Animation("torus", field="rotate:0,1,0", size=(64, 48))
    anim.step(12)
    anim.save_png(str(tmp_path / "py.png"))
    assert (tmp_path / "cli.png").read_bytes() == (tmp_path / "py.png").read_bytes()


def test_images_are_views_and_the_texture_is_float():
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=(80, 60))
    anim.step(3)
    image = anim.image()
    assert image.shape == (60, 80, 4) and not image.flags.owndata
    tex = anim.texture()
    assert tex.dtype == np.float32 and tex.shape == (60, 80, 4)
    assert anim.frame == 3 and anim.size == (80, 60)


def test_live_settings_keep_the_animation_and_others_rebuild():
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=SIZE)
    anim.step(4)
    anim.set(alpha=0.3, background=(0, 0, 0), camera=(40, 20, 0))
    assert anim.frame == 4
    anim.step(1)
    assert (anim.image()[0, 0, :3] == 0).all()  # the new background, live
    anim.set(scale=4)  # a new noise grid: the texture goes on (as in the viewer)
    assert anim.frame == 5
    texture = anim.texture()
    anim.set(color_by="speed")  # the scene prepared again, over the same surface:
    assert anim.frame == 5  # the texture goes on from where it is
    assert np.array_equal(anim.texture(), texture)
    anim.set(subdivide=1)  # over another surface: the texture starts afresh
    assert anim.frame == 0
    with pytest.raises(ValueError, match="alpha"):
        anim.set(alpha=7)


def _correlation(a, b):
    """Correlation of two pictures' grey values where both show the surface
    (not the grey background of the corner)."""
    ga, gb = a[..., :3].mean(axis=-1), b[..., :3].mean(axis=-1)
    mask = (np.abs(ga - ga[0, 0]) > 2) & (np.abs(gb - gb[0, 0]) > 2)
    return float(np.corrcoef(ga[mask], gb[mask])[0, 1])


def test_update_takes_new_data_on_from_the_texture():
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=(96, 96))
    twin = ibfvs.Animation(p, t, v, size=(96, 96))
    anim.step(30)
    twin.step(30)
    before = np.array(anim.image())
    # The same data again: nothing changes, the picture is the twin's.
    anim.update(points=p, vectors=v)
    anim.step(1)
    twin.step(1)
    assert np.array_equal(anim.image(), twin.image())
    # Points that moved (the torus turned 3 degrees about +Y, its rotation
    # field with it), over 4 frames: the texture goes on.
    a = np.radians(3.0)
    turn = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    anim.update(points=p @ turn.T, vectors=v @ turn.T, frames=4)
    assert anim.frame == 35
    kept = _correlation(before, anim.image())
    anim.restart()  # only asked for does it start from noise
    anim.step(1)
    fresh = _correlation(before, anim.image())
    assert kept > 0.45 and fresh < 0.25, (kept, fresh)  # measured 0.60 (4 frames unchanged: 0.66), 0.14
    # Other triangles: taken on from the image.
    p2, t2, v2 = torus(n_major=60, n_minor=20)
    anim.update(points=p2, triangles=t2, vectors=v2)
    anim.step(2)
    with pytest.raises(ValueError, match="vectors has 7 rows"):
        anim.update(vectors=np.zeros((7, 3)))


def test_a_new_size_keeps_the_texture():
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=(96, 96))
    anim.step(30)
    anim.set(size=(192, 192))
    assert anim.size == (192, 192) and anim.frame == 30


def test_lock_iterate_and_video(tmp_path):
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=SIZE)
    frames = list(anim.frames(3))
    assert len(frames) == 3 and frames[0].shape == (64, 64, 3)
    anim.lock()
    assert anim.locked
    files = anim.export(str(tmp_path / "torus.glb"))
    assert files == [str(tmp_path / "torus.glb"), str(tmp_path / "torus.png")]
    assert all(os.path.getsize(f) > 100 for f in files)
    with pytest.raises(ValueError, match="must be a .obj"):
        anim.export(str(tmp_path / "torus.stl"))
    path = anim.write_video(str(tmp_path / "a.mp4"), 10)
    assert os.path.getsize(path) > 1000
    assert anim._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    video = anim.video(frames=3)
    assert video.data[4:8] == b"ftyp" and "<video" in video._repr_html_()


@pytest.mark.skipif(not ibfvs.Animation._has_page(), reason="built without the browser runtime")
def test_web_page_of_the_animation(tmp_path):
    import html
    import json
    import re

    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=SIZE, alpha=0.15)
    path = tmp_path / "torus.html"
    anim.to_html(path)
    page = path.read_text()
    header = json.loads(re.search(r'id="ibfvs-scene">(.*?)</script>', page).group(1))
    assert header["vertex_count"] == len(p) and header["index_count"] == 3 * len(t)
    assert [header["width"], header["height"]] == list(SIZE)
    own = header["looks"][0]  # the page's own look first, then other styles of the same data
    alpha = next(u for u in own["uniforms"] if u["name"] == "u_alpha")
    assert abs(alpha["values"][0] - 0.15) < 1e-6  # the settings in force
    assert "#version 300 es" in own["shaders"]["fragment"]
    inline = anim._repr_html_()
    assert inline.startswith("<iframe srcdoc=") and html.unescape(inline).count('id="ibfvs-scene"') == 1
    with pytest.raises(ValueError, match="must be named NAME.html"):
        anim.to_html(tmp_path / "torus.png")


def test_errors_are_exceptions_with_a_reason():
    p, t, v = torus()
    bad = p.copy()
    bad[5, 1] = np.nan
    with pytest.raises(ValueError, match="point 5 has a non-finite"):
        ibfvs.render(bad, t, v, size=SIZE, frames=1)
    out_of_range = t.copy()
    out_of_range[3, 2] = len(p) + 7
    with pytest.raises(ValueError, match="triangle 3 refers to point"):
        ibfvs.render(p, out_of_range, v, size=SIZE, frames=1)
    with pytest.raises(ValueError, match="shape"):
        ibfvs.render(p[:, :2], t, v, size=SIZE, frames=1)
    with pytest.raises(TypeError, match="integers"):
        ibfvs.render(p, t.astype(float), v, size=SIZE, frames=1)
    with pytest.raises(ValueError, match="rows"):
        ibfvs.render(p, t, v[:10], size=SIZE, frames=1)
    with pytest.raises(TypeError, match="unknown option 'alfa'"):
        ibfvs.render(p, t, v, size=SIZE, frames=1, alfa=0.2)
    with pytest.raises(ValueError, match="step"):
        ibfvs.render(p, t, v, size=SIZE, frames=1, step=-1)
    with pytest.raises(ValueError, match="no such file"):
        ibfvs.Animation("nowhere.off")


def test_bad_polygons_are_exceptions_with_a_reason():
    """A VTK-style cell list or polygon list that does not hold together is
    one ValueError naming what is wrong, never a crash."""
    points = np.zeros((4, 3))
    split = ibfvs._ibfvs.split_polygons
    with pytest.raises(ValueError, match="cell 1 says 5 points but the array ends before"):
        ibfvs._ibfvs.cells_of_faces(np.array([3, 0, 1, 2, 5, 0, 1]))
    with pytest.raises(ValueError, match="says -1 points"):
        ibfvs._ibfvs.cells_of_faces(np.array([-1, 0]))
    with pytest.raises(ValueError, match="offsets start at 0"):
        split(np.array([1, 3]), np.array([0, 1, 2]), points)
    with pytest.raises(ValueError, match="offset 2 is 2"):
        split(np.array([0, 3, 2]), np.array([0, 1, 2]), points)
    with pytest.raises(ValueError, match="end at 3, not at the 4 ids"):
        split(np.array([0, 3]), np.array([0, 1, 2, 3]), points)
    with pytest.raises(ValueError, match="id 2 is point 9 but there are 4 points"):
        split(np.array([0, 3]), np.array([0, 1, 9]), points)
    with pytest.raises(ValueError, match="offsets and ids must be flat"):
        split(np.zeros((2, 2), np.int64), np.array([0, 1, 2]), points)
    with pytest.raises(ValueError, match="cell 0 says 7 points"):
        ibfvs._faces_to_triangles(np.array([7, 0, 1]), points)


def test_the_gil_is_released_while_rendering():
    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=(256, 256))
    ticks = 0
    worker = threading.Thread(target=anim.step, args=(60,))
    worker.start()
    while worker.is_alive():
        ticks += 1
    worker.join()
    assert anim.frame == 60
    assert ticks > 1000  # Python ran beside the rendering


def test_keys_match_the_command():
    names = [k[0] for k in ibfvs.keys()]
    assert "alpha" in names and "image_normalize" in names and "style" in names


SQUARE_VTK = """# vtk DataFile Version 4.2
square
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0  1 0 0  1 1 0  0 1 0
POLYGONS 1 5
4 0 1 2 3
POINT_DATA 4
VECTORS v float
1 0 0  1 0 0  1 0 0  1 0 0
"""


@pytest.mark.skipif(not ibfvs.has_vtk, reason="built without ParaView's VTK")
def test_vtk_files_through_the_dataset_readers(tmp_path):
    path = tmp_path / "square.vtk"
    path.write_text(SQUARE_VTK)
    anim = ibfvs.Animation(path, vectors="v", size=SIZE)
    anim.step(3)
    assert anim.image().shape == (64, 64, 4)
    with pytest.raises(ValueError, match="no such array"):
        ibfvs.Animation(path, vectors="U", size=SIZE)


def test_ctrl_c_interrupts_a_long_step():
    import _thread
    import time

    p, t, v = torus()
    anim = ibfvs.Animation(p, t, v, size=(128, 128))
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        anim.step(100000)
    assert time.perf_counter() - start < 30
    assert 0 < anim.frame < 100000
    anim.step(1)  # still usable


@pytest.mark.skipif(not ibfvs.has_vtk, reason="a build without ParaView's VTK")
def test_the_pyvista_front_end_refuses_a_module_that_links_paraviews_vtk():
    """One VTK a process: this module links ParaView's VTK, so ibfvs.pyvista
    (PyPI's vtk) is refused before it loads a second one."""
    import sys

    with pytest.raises(ImportError, match="pip package"):
        import ibfvs.pyvista  # noqa: F401
    assert "pyvista" not in sys.modules


def test_the_widget_without_anywidget_says_how_to_install_it():
    """ibfvs.widget needs anywidget (the pip package's notebook extra); the
    build tree's Python has none: one ImportError that names the extra."""
    import importlib.util

    if importlib.util.find_spec("anywidget") is not None:
        pytest.skip("anywidget is installed: python/package_tests test the widget")
    with pytest.raises(ImportError, match=r"ibfvs\[notebook\]"):
        ibfvs.widget(mesh="torus", size=(32, 32))


def uv_sphere(rows=48, columns=72):
    """A unit sphere of rows x columns quads (its poles left open)."""
    th, ph = np.meshgrid(np.linspace(0.05, np.pi - 0.05, rows),
                         np.linspace(0, 2 * np.pi, columns, endpoint=False), indexing="ij")
    points = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], -1)
    points = points.reshape(-1, 3)
    tris = []
    for i in range(rows - 1):
        for j in range(columns):
            a, b = i * columns + j, i * columns + (j + 1) % columns
            tris += [(a, a + columns, b), (b, a + columns, b + columns)]
    return points, np.array(tris)


def test_topology_of_arrays_finds_the_closed_separation_line_and_its_reverse():
    points, tris = uv_sphere()
    axis = np.array([0.3, 0.2, 0.93]) / np.linalg.norm([0.3, 0.2, 0.93])
    z = points @ axis
    spiral = np.cross(axis, points) - z[:, None] * (axis - z[:, None] * points)
    found = ibfvs.topology(points, tris, spiral)
    assert found.count("separation line") == 1 and found.count("attachment line") == 0
    line = found.lines[0]
    assert line["closed"] and line["kind"] == 10
    assert np.abs(line["points"] @ axis).max() < 0.02  # on the great circle across the axis
    assert abs(line["length"] - 2 * np.pi) < 0.05
    # Its neighbours converge onto it at the pull's rate 1 per unit of length
    # along it: by e^(2 pi) a turn.
    assert line["strength"] == pytest.approx(2 * np.pi, abs=0.15) and line["origin"] == 2
    assert found.kind.tolist() == [5, 5] and found.index_sum == 2  # the two repelling foci
    assert np.allclose(np.abs(found.points @ axis), 1.0, atol=0.01)
    assert "open surface, 2 boundary loops" in found.summary  # the poles are holes
    reverse = ibfvs.topology(points, tris, -spiral)
    assert [ln["kind"] for ln in reverse.lines] == [11] and reverse.kind.tolist() == [4, 4]
    assert ibfvs.KINDS[10] == "separation line" and ibfvs.KIND_COLOURS[10][0] > 200


def test_topology_of_a_scene_and_its_errors():
    found = ibfvs.topology("torus", field="gradient:down:1,0,0.137")
    assert sorted(found.kind.tolist()) == [1, 1, 2, 3] and found.index_sum == 0
    assert found.euler_characteristic == 0
    assert np.allclose(np.linalg.norm(found.normals, axis=1), 1.0, atol=1e-4)
    zero = ibfvs.topology("torus", field="uniform:0,0,0")
    assert len(zero.kind) == 0 and not zero.lines and zero.zero_triangles == 20480
    points, tris = uv_sphere(8, 8)
    with pytest.raises(ValueError, match="vectors has 3 rows"):
        ibfvs.topology(points, tris, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="no such file"):
        ibfvs.topology("no-such-mesh.ply")


def test_topology_takes_what_animation_takes():
    """ibfvs.topology takes a series, a duck-typed mesh, NaN vectors and bad
    options as Animation and the command do: every step (its features' ids
    kept), a Topology of numpy arrays (no pyvista needed), a RuntimeWarning
    as Animation's warnings say, a ValueError."""
    winds = os.path.join(os.path.dirname(__file__), "..", "..", "data", "earth",
                         "monthly_navy_winds.cdf")
    if os.path.exists(winds):
        steps = ibfvs.topology("globe:3", field=f"wind:{winds}", time="0:2")
        assert isinstance(steps, list) and len(steps) == 3
        assert all(isinstance(s, ibfvs.Topology) for s in steps)
        assert all(f"step {k}:" in s.summary for k, s in enumerate(steps))
        # A feature that lasts keeps its id: most of step 1's points are step 0's.
        first, second = set(steps[0].id.tolist()), set(steps[1].id.tolist())
        assert len(first & second) >= len(second) // 2
    points, tris = uv_sphere()
    axis = np.array([0.3, 0.2, 0.93]) / np.linalg.norm([0.3, 0.2, 0.93])
    z = points @ axis
    spiral = np.cross(axis, points) - z[:, None] * (axis - z[:, None] * points)

    class Mesh:  # points and a VTK-style faces array, as PyVista's, but no PyVista
        pass

    duck = Mesh()
    duck.points = points
    duck.faces = np.column_stack([np.full(len(tris), 3), tris]).ravel()
    duck.point_data = {"spiral": spiral}
    found = ibfvs.topology(duck, vectors="spiral")
    assert isinstance(found, ibfvs.Topology) and found.count("separation line") == 1
    holey = spiral.copy()
    holey[10] = np.nan
    with pytest.warns(RuntimeWarning, match="NaN or infinite"):
        found = ibfvs.topology(points, tris, holey)
    assert found.count("separation line") == 1
    for bad in (dict(min_strength=-1), dict(min_length=-1), dict(feature_scale=0), dict(feature_scale=2)):
        with pytest.raises(ValueError, match="topology"):
            ibfvs.topology(points, tris, spiral, **bad)


def test_the_topologys_layout_is_the_commands():
    """The arrays of ibfvs.topology are those of `ibfvs topology`'s .vtp (one
    layout): the same points, cells, kinds, ids, strengths and colours."""
    import xml.etree.ElementTree as ET

    exe = os.environ.get("IBFVS_EXE")
    if not exe:
        pytest.skip("IBFVS_EXE (the command) not set")
    found = ibfvs.topology("torus", field="gradient:down:1,0,0.137")
    out = os.path.join(os.environ.get("TMPDIR", "/tmp"), "ibfvs_layout_%d.vtp" % os.getpid())
    subprocess.run([exe, "topology", "torus", "--field", "gradient:down:1,0,0.137", "-o", out, "-q"],
                   check=True)
    arrays = {a.get("Name"): a.text.split() for a in ET.parse(out).getroot().iter("DataArray")}
    os.remove(out)
    g = found.layout
    assert np.allclose(np.asarray(arrays["Points"], float), np.asarray(g["points"]).ravel(), atol=1e-6)
    for name in ("kind", "id", "origin"):
        assert [int(x) for x in arrays[name]] == np.asarray(g[name]).tolist(), name
    assert np.allclose(np.asarray(arrays["strength"], float), g["strength"], rtol=1e-6, atol=1e-9)
    assert [int(x) for x in arrays["colour"]] == np.asarray(g["colour"]).ravel().tolist()
    assert [ibfvs.KIND_COLOURS[k] for k in np.asarray(g["kind"]).tolist()] == [
        tuple(c) for c in np.asarray(g["colour"]).tolist()]


def test_the_overlay_key_draws_the_topology_in_the_modules_pictures():
    """overlay="topology" is a scene key like any other: ibfvs.render's
    picture has the separation line's red and the foci's pink, without it
    none."""
    points, tris = uv_sphere(64, 96)
    axis = np.array([0.0, 1.0, 0.0])
    z = points @ axis
    spiral = np.cross(axis, points) - z[:, None] * (axis - z[:, None] * points)

    def count(image, rgb):
        return int((np.abs(image[..., :3].astype(int) - np.array(rgb)).max(axis=2) < 30).sum())

    kw = dict(size=(200, 200), frames=10, camera="0,20,0")
    over = ibfvs.render(points, tris, spiral, overlay="topology", **kw)
    plain = ibfvs.render(points, tris, spiral, **kw)
    red, pink = ibfvs.KIND_COLOURS[10], ibfvs.KIND_COLOURS[5]
    assert count(over, red) > 50 and count(over, pink) > 5
    assert count(plain, red) == 0 and count(plain, pink) == 0


def test_a_netcdf_fields_steps_are_named_by_the_dates_of_its_time_axis():
    """step_labels: the Navy winds' months from the file's time axis (hours
    since 1980-01-14 14:00), following the time key; a scene without one
    has none."""
    winds = os.path.join(os.path.dirname(__file__), "..", "..", "data", "earth",
                         "monthly_navy_winds.cdf")
    if not os.path.exists(winds):
        pytest.skip("fetched data missing (scripts/fetch_data.sh)")
    year = ibfvs.Animation("globe:2", field=f"wind:{winds}", time="0:11", size=(16, 16), frames=1)
    assert year.step_count == 12
    assert [label[:7] for label in year.step_labels] == [f"1982-{m:02d}" for m in range(1, 13)]
    assert year.step_labels[0] == "1982-01-16 20:00"
    july = ibfvs.Animation("globe:2", field=f"wind:{winds}", time=6, size=(16, 16), frames=1)
    assert july.step_labels == ["1982-07-18 11:00"]
    july.set(time="130:131")
    assert july.step_labels == ["1992-11-16 17:00", "1992-12-17 03:30"]
    p, t, v = torus()
    assert ibfvs.Animation(p, t, v, size=(16, 16)).step_labels == []
