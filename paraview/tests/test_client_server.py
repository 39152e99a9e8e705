"""Client-server, as users run large cases: a pvserver (one rank, and two
under MPI) with the plugin loaded on both sides, a pvpython client that
connects, forces remote rendering (the server draws, the client gets the
picture) and gets the picture a builtin session draws of the same scene;
the page the client exports holds the whole surface. Run with
test_plugin.py (its helpers and display)."""
import contextlib
import json
import os
import signal
import socket
import subprocess
import threading
from pathlib import Path

import numpy as np
import pytest

from test_plugin import DISPLAY, MPIEXEC, data, image, pytestmark, run, xvfb  # noqa: F401


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def pvserver(ranks):
    """A pvserver on the module's display, `ranks` processes; yields its
    HOST:PORT once it accepts connections. It ends when its client leaves."""
    port = free_port()
    cmd = ["pvserver", "--server-port=%d" % port]
    if ranks > 1:
        cmd = [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + cmd
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=dict(os.environ, DISPLAY=DISPLAY["name"]),
                            start_new_session=True)
    said, ready = [], threading.Event()

    def read():
        for line in proc.stdout:
            said.append(line)
            if "Accepting connection" in line:
                ready.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        assert ready.wait(60), "pvserver did not start: " + "".join(said)
        yield "localhost:%d" % port
        proc.wait(timeout=60)  # the client left: the server ends
        assert proc.returncode == 0, "".join(said)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        reader.join(timeout=10)


@pytest.mark.parametrize("ranks", [1, 2], ids=["1-rank", "2-ranks"])
def test_a_client_of_pvserver_gets_the_builtin_sessions_picture(data, tmp_path, ranks):
    if ranks > 1 and MPIEXEC is None:
        pytest.skip("needs mpiexec")
    # Without FXAA: under MPI ParaView antialiases the composited image
    # (docs/paraview.md); the sphere in two pieces, coloured by height.
    cfg = {"data": str(data / "sphere.pvtp"), "vectors": ["POINTS", "v"], "frames": 40,
           "shots": [40], "pieces": True, "fxaa": False, "color": ["POINTS", "height"]}
    _, builtin = run(dict(cfg, name="builtin"), tmp_path)
    page = tmp_path / "client.html"
    with pvserver(ranks) as address:
        done, client = run(dict(cfg, name="client", server=address, remote_render=True,
                                export={"file": str(page)}), tmp_path)
    assert json.loads(Path(client + ".json").read_text())["remote"], "the client drew it"
    if ranks > 1:  # the server's ranks each read a piece
        pieces = image(client + "-pieces.png").reshape(-1, 3)
        assert len(np.unique(pieces // 32, axis=0)) >= 3  # two pieces' colours and the background
    one, other = image(builtin + "-40.png"), image(client + "-40.png")
    differ = np.abs(one - other).max(axis=-1) > 2
    print("client of %d rank(s): %d pixels differ from the builtin session's" % (
        ranks, differ.sum()))
    assert differ.mean() < 0.001, "%d pixels differ" % differ.sum()
    # File > Export Scene from the client: the whole surface, however the
    # server split it.
    assert "ibfvs-test: exported" in done.stdout, done.stdout + done.stderr
    header = json.loads(page.read_text().split('id="ibfvs-scene">', 1)[1].split("</script>")[0])
    assert header["index_count"] == 3 * 36096
