"""What the tests that run a server on this machine share (JupyterLab's,
trame's): a free port on the loopback, and the wait until it answers."""

import socket
import time
import urllib.request

import pytest


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until_up(url, process, log, what, tries=120):
    """Until URL answers; a failed test with the server's log when the
    process ends first or a minute passes."""
    for _ in range(tries):
        try:
            urllib.request.urlopen(url, timeout=2)
            return
        except OSError:
            if process.poll() is not None:
                break
            time.sleep(0.5)
    pytest.fail(f"{what} did not start: " + log.read_text()[-2000:])
