"""The command `ibfvs` of the pip package: runs the program installed beside
the module (ibfvs/bin/ibfvs) with the same arguments, standard streams and
exit status, as `python -m ibfvs` does too."""

from __future__ import annotations

import os
import sys
from pathlib import Path


def command_path() -> Path:
    """The command's program in this installation of the package."""
    return Path(__file__).resolve().parent / "bin" / "ibfvs"


def main() -> None:
    exe = command_path()
    if not exe.is_file():
        sys.exit(f"ibfvs: the command's program is missing from this installation ({exe}); "
                 "build trees run build/ibfvs")
    # The pip package's video goes through imageio-ffmpeg's ffmpeg (or one on
    # PATH): named for the program in IBFVS_FFMPEG.
    from ._external import find_ffmpeg

    find_ffmpeg()
    os.execv(exe, [str(exe), *sys.argv[1:]])


if __name__ == "__main__":
    main()
