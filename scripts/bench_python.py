#!/usr/bin/env python3
"""Python against the command: 300 frames at 512x512 of the same scene, each
run in a fresh process (the command's own timing line, and wall clock for
both), alternating; then a frame's round trip into numpy.

Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/bench_python.py [MESH] [RUNS]
"""

import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESH = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "data/meshes/cow.off")
RUNS = int(sys.argv[2]) if len(sys.argv) > 2 else 3
EXE = os.path.join(ROOT, "build/ibfvs")
FRAMES, SIZE = 300, (512, 512)

PY = f"""
import time, ibfvs
t0 = time.perf_counter()
anim = ibfvs.Animation({MESH!r}, size={SIZE})
t1 = time.perf_counter()
anim.step({FRAMES})
anim.image()
t2 = time.perf_counter()
print(f"{{t1 - t0:.3f}} {{t2 - t1:.3f}}")
"""


def wall(cmd, env=None):
    t = time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    return time.perf_counter() - t, out


env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "build/python"))
cli, cli_frames, py, py_frames = [], [], [], []
for _ in range(RUNS):
    t, out = wall([EXE, "render", "--mesh", MESH, "--frames", str(FRAMES), "--size",
                   f"{SIZE[0]}x{SIZE[1]}", "--out", "/tmp/ibfvs-bench-cli.png"])
    cli.append(t)
    fps = float(re.search(r"([0-9.]+) fps", out).group(1))  # the command's frame loop
    cli_frames.append(FRAMES / fps)
    t, out = wall([sys.executable, "-c", PY], env)
    py.append(t)
    py_frames.append(float(out.split()[1]))
print(f"command, whole process: {' '.join(f'{t:.2f}' for t in cli)} s")
print(f"python,  whole process: {' '.join(f'{t:.2f}' for t in py)} s")
print(f"command, 300 frames alone: {' '.join(f'{t:.2f}' for t in cli_frames)} s")
print(f"python,  300 frames alone: {' '.join(f'{t:.2f}' for t in py_frames)} s")
print(f"best, whole process: python / command = {min(py) / min(cli):.3f}")
print(f"best, 300 frames:    python / command = {min(py_frames) / min(cli_frames):.3f}")

sys.path.insert(0, os.path.join(ROOT, "build/python"))
import numpy as np  # noqa: E402
import ibfvs  # noqa: E402

anim = ibfvs.Animation(MESH, size=SIZE)
anim.step(5)
for name, grab in (("image() view", lambda: anim.image()),
                   ("np.array(image()) copy", lambda: np.array(anim.image())),
                   ("texture() view", lambda: anim.texture())):
    n = 50
    t = time.perf_counter()
    for _ in range(n):
        grab()
    print(f"{name}: {(time.perf_counter() - t) / n * 1000:.2f} ms per frame")
t = time.perf_counter()
for _ in range(50):
    anim.step()
print(f"step(): {(time.perf_counter() - t) / 50 * 1000:.2f} ms per frame")
