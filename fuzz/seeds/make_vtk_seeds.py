"""Writes the VTK fuzzers' seeds (committed in fuzz/corpus/{vtk,vtp,vtu}_fuzzer):
a small surface with point and cell arrays (a vector, a scalar, a 2-component
array) in legacy ASCII and binary, XML ASCII, binary, appended raw and
compressed. Run with ParaView's Python: pvpython make_vtk_seeds.py OUT_DIR"""
import os
import sys

from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkFiltersCore import vtkAppendFilter
from vtkmodules.vtkIOLegacy import vtkPolyDataWriter, vtkUnstructuredGridWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter, vtkXMLUnstructuredGridWriter

out = sys.argv[1]
sphere = vtkSphereSource()
sphere.SetThetaResolution(5)
sphere.SetPhiResolution(4)
sphere.Update()
poly = sphere.GetOutput()


def array(name, components, count, scale):
    a = vtkFloatArray()
    a.SetName(name)
    a.SetNumberOfComponents(components)
    a.SetNumberOfTuples(count)
    for i in range(count):
        for c in range(components):
            a.SetComponent(i, c, scale * (i + 1) * (c + 1))
    return a


poly.GetPointData().AddArray(array("U", 3, poly.GetNumberOfPoints(), 0.1))
poly.GetPointData().AddArray(array("p", 1, poly.GetNumberOfPoints(), 0.5))
poly.GetCellData().AddArray(array("wallShearStress", 3, poly.GetNumberOfCells(), 0.01))
poly.GetCellData().AddArray(array("uv", 2, poly.GetNumberOfCells(), 1.0))
append = vtkAppendFilter()
append.AddInputData(poly)
append.Update()
grid = append.GetOutput()

for kind, data, legacy, xml in (("vtk", poly, vtkPolyDataWriter, None),
                                 ("vtk", grid, vtkUnstructuredGridWriter, None),
                                 ("vtp", poly, None, vtkXMLPolyDataWriter),
                                 ("vtu", grid, None, vtkXMLUnstructuredGridWriter)):
    folder = os.path.join(out, kind + "_fuzzer")
    os.makedirs(folder, exist_ok=True)
    stem = "polydata" if data is poly else "grid"
    if legacy:
        # Version 5.1 (offsets and connectivity) and 4.2 (cell records).
        for binary in (False, True):
            for version, suffix in ((51, ""), (42, "-v4")):
                w = legacy()
                w.SetInputData(data)
                w.SetFileVersion(version)
                encoding = "binary" if binary else "ascii"
                w.SetFileName(os.path.join(folder, f"{stem}-{encoding}{suffix}.vtk"))
                w.SetFileTypeToBinary() if binary else w.SetFileTypeToASCII()
                w.Write()
    else:
        for mode in ("ascii", "binary", "appended", "compressed"):
            w = xml()
            w.SetInputData(data)
            w.SetFileName(os.path.join(folder, f"{stem}-{mode}.{kind}"))
            if mode == "ascii":
                w.SetDataModeToAscii()
            elif mode == "binary":
                w.SetDataModeToBinary()
                w.SetCompressorTypeToNone()
            elif mode == "appended":
                w.SetDataModeToAppended()
                w.EncodeAppendedDataOff()
                w.SetCompressorTypeToNone()
            else:
                w.SetDataModeToAppended()
                w.SetCompressorTypeToZLib()
            w.Write()
