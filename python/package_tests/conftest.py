"""The pip package's tests: run by scripts/python-package.sh in a fresh venv
with the built wheel, the pinned pyvista and vtk, never the build tree.

VTK draws headless through EGL (the vtk wheel's EGL window): no display."""

import os

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
