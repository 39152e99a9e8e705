"""The wheel itself (docs/python.md, "The wheel"): what it bundles, held to an
allowlist; its size; auditwheel's verdict; the libraries found where it is
installed; video through the ffmpeg of Python's own packages; netCDF
through xarray, read as the Debian build's netCDF-C reads it."""

import os
import re
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import ibfvs

# What drawing the texture needs, and nothing else: the mesh readers
# (OpenMesh, tinygltf, stb for images, b64 for the page), the GL loader
# (epoxy: the system's libEGL and libGL are loaded at run time), PNG,
# meshoptimizer, toml++, OpenMP's runtime, and GLFW for the viewer
# (`ibfvs view`; it links the system's libX11, which Mesa's EGL brings).
ALLOWED = {
    "libOpenMeshCore", "libtinygltf", "libstb", "libb64", "libepoxy", "libpng16",
    "libmeshoptimizer", "libtomlplusplus", "libgomp", "libglfw",
}
MAX_BYTES = 15 * 1024 * 1024


def wheel_path():
    wheel = os.environ.get("IBFVS_WHEEL")
    if not wheel:
        pytest.skip("run by scripts/python-package.sh or scripts/clean-room.sh, which set IBFVS_WHEEL")
    return wheel


def ibfvs_command():
    exe = shutil.which("ibfvs", path=os.path.dirname(sys.executable))
    assert exe, "the console script ibfvs is not installed beside this Python"
    return exe


def test_the_wheel_bundles_only_what_drawing_needs():
    wheel = wheel_path()
    assert os.path.getsize(wheel) <= MAX_BYTES, f"{wheel}: {os.path.getsize(wheel)} bytes"
    with zipfile.ZipFile(wheel) as z:
        libs = [n.split("/", 1)[1] for n in z.namelist()
                if n.startswith("ibfvs.libs/") and not n.endswith("/")]
    # auditwheel names a copy NAME-HASH.so.VERSION
    names = {re.sub(r"-[0-9a-f]{8}\.so.*$", "", lib) for lib in libs}
    assert names <= ALLOWED, f"bundled beyond the allowlist: {sorted(names - ALLOWED)}"
    assert "libepoxy" in names and "libOpenMeshCore" in names, libs


def test_auditwheel_finds_it_consistent_with_a_manylinux_tag():
    wheel = wheel_path()
    tool = os.environ.get("IBFVS_AUDITWHEEL")
    if not tool:
        pytest.skip("run by scripts/python-package.sh, which sets IBFVS_AUDITWHEEL")
    shown = " ".join(subprocess.run([tool, "show", wheel], capture_output=True, text=True,
                                    check=True).stdout.split())
    assert re.search(r'consistent with the following platform tag: "manylinux_2_\d+_x86_64"', shown), shown
    assert "external shared libraries" not in shown, shown
    tag = re.search(r'"(manylinux_2_\d+_x86_64)"', shown).group(1)
    assert tag in os.path.basename(wheel), (tag, wheel)


def test_the_module_and_the_command_find_every_library():
    package = os.path.dirname(ibfvs.__file__)
    for binary in (ibfvs._ibfvs.__file__, os.path.join(package, "bin", "ibfvs")):
        linked = subprocess.run(["ldd", binary], capture_output=True, text=True,
                                check=True).stdout
        assert "not found" not in linked, linked
        for name in ("libpng", "libepoxy", "libOpenMesh"):
            for line in linked.splitlines():
                if name in line:
                    assert "ibfvs.libs" in line, f"{name} from the system: {line}"
        for name in ("libavcodec", "libnetcdf", "libssl", "libcrypto", "libgnutls", "libcurl"):
            assert name not in linked, f"{binary} links {name}"
    assert not ibfvs._ibfvs.has_libav and not ibfvs._ibfvs.has_netcdf


def decoded(path):
    """The frames of a video as imageio-ffmpeg's ffmpeg decodes them."""
    import imageio_ffmpeg

    reader = imageio_ffmpeg.read_frames(str(path))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8).reshape(meta["size"][1], meta["size"][0], 3)
              for f in reader]
    return meta, frames


def test_the_console_script_writes_a_video(tmp_path):
    """`ibfvs render --out x.mp4` (and .webm, .gif) through imageio-ffmpeg's
    program: the frames all there, the size as asked (an odd one padded
    to even), and the texture moving from frame to frame."""
    for name, size in (("torus.mp4", "95x64"), ("torus.webm", "64x64"), ("torus.gif", "64x48")):
        out = tmp_path / name
        done = subprocess.run([ibfvs_command(), "render", "--mesh", "torus", "--field", "rotate:0,1,0",
                               "--frames", "12", "--size", size, "--out", str(out)],
                              capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        meta, frames = decoded(out)
        w, h = (int(v) for v in size.split("x"))
        if not name.endswith(".gif"):
            w, h = w + w % 2, h + h % 2
        assert tuple(meta["size"]) == (w, h), (name, meta)
        assert len(frames) == 12, (name, len(frames))
        assert np.abs(frames[-1].astype(int) - frames[-2].astype(int)).mean() > 1.0, name


def test_video_without_an_ffmpeg_is_one_clear_error(tmp_path):
    package = os.path.dirname(ibfvs.__file__)
    exe = os.path.join(package, "bin", "ibfvs")  # the program itself: no Python finds ffmpeg for it
    env = {k: v for k, v in os.environ.items() if k != "IBFVS_FFMPEG"}
    env["PATH"] = str(tmp_path)  # no ffmpeg there
    done = subprocess.run([exe, "render", "--mesh", "torus", "--frames", "2", "--size", "32x32",
                           "--out", str(tmp_path / "x.mp4")], capture_output=True, text=True, env=env)
    assert done.returncode != 0
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "x.mp4" in lines[0] and "imageio-ffmpeg" in lines[0], done.stderr
    env["IBFVS_FFMPEG"] = str(tmp_path / "nothing")
    done = subprocess.run([exe, "render", "--mesh", "torus", "--frames", "2", "--size", "32x32",
                           "--out", str(tmp_path / "x.mp4")], capture_output=True, text=True, env=env)
    assert done.returncode != 0 and "IBFVS_FFMPEG" in done.stderr, done.stderr
    assert not (tmp_path / "x.mp4").exists()


def test_animation_writes_a_video(tmp_path):
    anim = ibfvs.Animation("torus", field="rotate:0,1,0", size=(48, 48))
    anim.write_video(tmp_path / "a.mp4", 6, 24.0)
    meta, frames = decoded(tmp_path / "a.mp4")
    assert len(frames) == 6 and tuple(meta["size"]) == (48, 48)


def test_netcdf_is_read_through_xarray_as_the_debian_build_reads_it(tmp_path):
    """The earth's winds (the paper's figure 6 data): the wheel reads them
    with xarray, the Debian build's command with netCDF-C, and both draw the
    same picture and date the months alike."""
    pytest.importorskip("xarray")
    source = os.environ.get("IBFVS_SOURCE_DIR", "")
    winds = os.path.join(source, "data", "earth", "monthly_navy_winds.cdf")
    debian = os.path.join(source, "build", "ibfvs")
    if not os.path.exists(winds) or not os.path.exists(debian):
        pytest.skip("needs the checkout's data (scripts/fetch_data.sh) and its Release build")
    field = f"wind:{winds}:UWND:VWND"
    ours = ibfvs.render("globe", field=field, time=6, size=(96, 96), frames=20, camera=(80, 10, 0))
    png = tmp_path / "debian.png"
    done = subprocess.run([debian, "render", "--mesh", "globe", "--field", field, "--time", "6",
                           "--size", "96x96", "--frames", "20", "--camera", "80,10,0", "--out",
                           str(png)], check=True, capture_output=True, text=True)
    from PIL import Image

    theirs = np.asarray(Image.open(png).convert("RGB")).astype(int)
    difference = np.abs(ours.astype(int) - theirs)
    assert ours.std() > 20, "no texture"
    assert difference.mean() < 0.5 and (difference > 8).mean() < 0.002, difference.mean()
    # The months' dates: xarray's time axis here, netCDF-C's in the command.
    year = ibfvs.Animation("globe:1", field=field, time="0:131", size=(16, 16), frames=1)
    assert len(year.step_labels) == 132 and year.step_labels[0] == "1982-01-16 20:00"
    assert f"at time index 6 ({year.step_labels[6]})" in done.stdout, done.stdout


def test_a_file_that_is_not_netcdf_is_one_error_naming_it(tmp_path):
    pytest.importorskip("xarray")
    bad = tmp_path / "winds.nc"
    bad.write_bytes(b"CDF\x01 but not really")
    with pytest.raises(ValueError, match="winds.nc"):
        ibfvs.render("globe", field=f"wind:{bad}:U:V", size=(32, 32), frames=1)
    with pytest.raises(ValueError, match="no such file"):
        ibfvs.render("globe", field=f"wind:{tmp_path}/none.nc:U:V", size=(32, 32), frames=1)
