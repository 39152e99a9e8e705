# Writes the corpus of files that ParaView and its VTK write, under pvpython
# (run by test_real_files.py, never imported by it: one VTK per process).
# Every dataset carries a point vector array "v" (a swirl about z plus an
# upward part), a point scalar "height" and a cell scalar "cellid", so that
# `ibfvs render --field file:v` has a flow on every surface.
#   pvpython write_vtk_files.py OUT_DIR
# Prints one JSON line per file: {"file": ..., "kind": ..., "writer": ...}.
import json
import os
import sys

from paraview import simple as pv
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray, vtkIdTypeArray
from vtkmodules.vtkCommonDataModel import (vtkMultiBlockDataSet, vtkPartitionedDataSet,
                                           vtkPartitionedDataSetCollection, vtkPolyData,
                                           vtkRectilinearGrid)
from vtkmodules.vtkFiltersCore import vtkAppendFilter, vtkArrayCalculator
from vtkmodules.vtkFiltersGeneral import vtkImageDataToPointSet
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOLegacy import vtkDataSetWriter, vtkGenericDataObjectWriter
from vtkmodules.vtkIOParallelXML import (vtkXMLPartitionedDataSetCollectionWriter,
                                         vtkXMLPartitionedDataSetWriter)
from vtkmodules.vtkIOXML import (vtkXMLImageDataWriter, vtkXMLMultiBlockDataWriter,
                                 vtkXMLPolyDataWriter, vtkXMLRectilinearGridWriter,
                                 vtkXMLStructuredGridWriter, vtkXMLUnstructuredGridWriter)

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
written = []


def note(name, kind, writer):
    written.append({"file": os.path.join(out, name), "kind": kind, "writer": writer})


def with_arrays(data):
    """The arrays every file carries, computed by VTK's own calculator."""
    calc = vtkArrayCalculator()
    calc.SetInputData(data)
    calc.SetAttributeTypeToPointData()
    calc.AddCoordinateScalarVariable("x", 0)
    calc.AddCoordinateScalarVariable("y", 1)
    calc.AddCoordinateScalarVariable("z", 2)
    calc.SetFunction("(0-y)*iHat + x*jHat + 0.3*kHat")
    calc.SetResultArrayName("v")
    calc.Update()
    h = vtkArrayCalculator()
    h.SetInputData(calc.GetOutput())
    h.AddCoordinateScalarVariable("z", 2)
    h.SetFunction("z")
    h.SetResultArrayName("height")
    h.Update()
    result = h.GetOutput().NewInstance()
    result.DeepCopy(h.GetOutput())
    ids = vtkIdTypeArray()
    ids.SetName("cellid")
    for i in range(result.GetNumberOfCells()):
        ids.InsertNextValue(i)
    result.GetCellData().AddArray(ids)
    return result


def sphere(theta=48, phi=24, centre=(0, 0, 0)):
    s = vtkSphereSource()
    s.SetThetaResolution(theta)
    s.SetPhiResolution(phi)
    s.SetCenter(*centre)
    s.Update()
    return with_arrays(s.GetOutput())


def unstructured(poly):
    a = vtkAppendFilter()
    a.AddInputData(poly)
    a.Update()
    return a.GetOutput()


def image():
    w = vtkRTAnalyticSource()
    w.SetWholeExtent(-8, 8, -8, 8, -8, 8)
    w.Update()
    img = w.GetOutput()
    img.SetSpacing(0.1, 0.1, 0.1)
    return with_arrays(img)


def structured():
    p = vtkImageDataToPointSet()
    p.SetInputData(image())
    p.Update()
    return with_arrays(p.GetOutput())


def rectilinear():
    g = vtkRectilinearGrid()
    g.SetDimensions(9, 7, 5)
    for axis, n in zip((g.SetXCoordinates, g.SetYCoordinates, g.SetZCoordinates), (9, 7, 5)):
        c = vtkDoubleArray()
        for i in range(n):
            c.InsertNextValue(-1.0 + 2.0 * (i / (n - 1)) ** 1.5)
        axis(c)
    return with_arrays(g)


def xml(writer_class, name, data, kind, **settings):
    """One XML writer's file in its three encodings (ascii, inline binary,
    appended raw), compressed and not, 32- and 64-bit headers."""
    variants = [
        ("ascii", dict(DataMode=0)),
        ("binary", dict(DataMode=1)),
        ("appended", dict(DataMode=2, EncodeAppendedData=0)),
        ("appended-base64", dict(DataMode=2, EncodeAppendedData=1)),
        ("binary-uint64-zlib", dict(DataMode=1, HeaderType=64, Compressor="zlib")),
        ("appended-lz4", dict(DataMode=2, EncodeAppendedData=0, Compressor="lz4")),
        ("binary-lzma", dict(DataMode=1, Compressor="lzma")),
    ]
    base, ext = os.path.splitext(name)
    for tag, options in variants:
        w = writer_class()
        w.SetInputData(data)
        file = "%s-%s%s" % (base, tag, ext)
        w.SetFileName(os.path.join(out, file))
        w.SetDataMode(options["DataMode"])
        if "EncodeAppendedData" in options:
            w.SetEncodeAppendedData(options["EncodeAppendedData"])
        if options.get("HeaderType") == 64:
            w.SetHeaderTypeToUInt64()
        compressor = options.get("Compressor")
        if compressor == "zlib":
            w.SetCompressorTypeToZLib()
        elif compressor == "lz4":
            w.SetCompressorTypeToLZ4()
        elif compressor == "lzma":
            w.SetCompressorTypeToLZMA()
        else:
            w.SetCompressorTypeToNone()
        assert w.Write() == 1, file
        note(file, kind, writer_class.__name__ + " " + tag)


poly = sphere()
xml(vtkXMLPolyDataWriter, "sphere.vtp", poly, "polydata")
xml(vtkXMLUnstructuredGridWriter, "sphere.vtu", unstructured(poly), "unstructured grid")
xml(vtkXMLImageDataWriter, "wavelet.vti", image(), "image data")
xml(vtkXMLStructuredGridWriter, "wavelet.vts", structured(), "structured grid")
xml(vtkXMLRectilinearGridWriter, "grid.vtr", rectilinear(), "rectilinear grid")

# Legacy files: every dataset kind, ASCII and binary, VTK 9's 5.1 layout and
# the 4.2 layout older readers take.
for name, data in [("sphere", poly), ("sphere-ug", unstructured(poly)), ("wavelet", image()),
                   ("wavelet-sg", structured()), ("grid", rectilinear())]:
    for binary in (False, True):
        for version in ("5.1", "4.2"):
            w = vtkGenericDataObjectWriter()
            w.SetInputData(data)
            file = "%s-%s-%s.vtk" % (name, "binary" if binary else "ascii", version)
            w.SetFileName(os.path.join(out, file))
            if binary:
                w.SetFileTypeToBinary()
            else:
                w.SetFileTypeToASCII()
            if version == "4.2":
                w.SetFileVersion(42)
            assert w.Write() == 1, file
            note(file, "legacy " + data.GetClassName(), "vtkGenericDataObjectWriter")

def write_composite(writer_class, data, name, kind):
    w = writer_class()
    w.SetInputData(data)
    w.SetFileName(os.path.join(out, name))
    assert w.Write() == 1, name
    note(name, kind, writer_class.__name__)


# Composite data: a multiblock (nested, named blocks), a partitioned data set
# and a partitioned collection, as ParaView 5.11 writes them.
mb = vtkMultiBlockDataSet()
inner = vtkMultiBlockDataSet()
inner.SetBlock(0, sphere(centre=(2.5, 0, 0)))
inner.GetMetaData(0).Set(vtkMultiBlockDataSet.NAME(), "right")
mb.SetBlock(0, poly)
mb.GetMetaData(0).Set(vtkMultiBlockDataSet.NAME(), "middle")
mb.SetBlock(1, inner)
mb.GetMetaData(1).Set(vtkMultiBlockDataSet.NAME(), "group")
write_composite(vtkXMLMultiBlockDataWriter, mb, "blocks.vtm", "multiblock")
pd = vtkPartitionedDataSet()
pd.SetPartition(0, sphere(centre=(-2.5, 0, 0)))
pd.SetPartition(1, unstructured(sphere(centre=(2.5, 0, 0))))
write_composite(vtkXMLPartitionedDataSetWriter, pd, "parts.vtpd", "partitioned")
pc = vtkPartitionedDataSetCollection()
pc.SetPartitionedDataSet(0, pd)
write_composite(vtkXMLPartitionedDataSetCollectionWriter, pc, "collection.vtpc",
                "partitioned collection")

# ParaView's own writers through paraview.simple, as File > Save Data does:
# serial and parallel XML, legacy, a multiblock, and a time series as .pvd
# (the swirl growing over three steps).
src = pv.Sphere(ThetaResolution=40, PhiResolution=20)
calc = pv.Calculator(Input=src, ResultArrayName="v", Function="(0-coordsY)*iHat+coordsX*jHat+0.3*kHat")
for name in ("pv-sphere.vtp", "pv-sphere.pvtp", "pv-sphere-legacy.vtk"):
    pv.SaveData(os.path.join(out, name), proxy=calc)
    note(name, "paraview " + os.path.splitext(name)[1], "paraview.simple.SaveData")
ug = pv.MergeBlocks(Input=calc)
pv.SaveData(os.path.join(out, "pv-sphere.pvtu"), proxy=ug)
note("pv-sphere.pvtu", "paraview .pvtu", "paraview.simple.SaveData")
pv.SaveData(os.path.join(out, "pv-blocks.vtm"), proxy=pv.GroupDatasets(Input=[calc, ug]))
note("pv-blocks.vtm", "paraview .vtm", "paraview.simple.SaveData")

# A temporal source: three steps of the same sphere with the swirl scaled.
steps = []
os.makedirs(os.path.join(out, "series"), exist_ok=True)
for k in range(3):
    c = pv.Calculator(Input=src, ResultArrayName="v",
                      Function="%g*((0-coordsY)*iHat+coordsX*jHat+0.3*kHat)" % (1 + k))
    file = "step_%d.vtp" % k
    pv.SaveData(os.path.join(out, "series", file), proxy=c)
    steps.append((k * 0.5, file))
with open(os.path.join(out, "series", "steps.pvd"), "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n')
    for t, file in steps:
        f.write('  <DataSet timestep="%g" part="0" file="%s"/>\n' % (t, file))
    f.write("</Collection>\n</VTKFile>\n")
note(os.path.join("series", "steps.pvd"), "pvd time series", "written beside SaveData's files")
with open(os.path.join(out, "series", "steps.vtp.series"), "w") as f:
    json.dump({"file-series-version": "1.0",
               "files": [{"name": file, "time": t} for t, file in steps]}, f, indent=2)
note(os.path.join("series", "steps.vtp.series"), ".series time series",
     "written beside SaveData's files")
# The same steps read back as ParaView's file series and saved as one .pvd
# by ParaView's PVD writer (every time step).
reader = pv.XMLPolyDataReader(FileName=[os.path.join(out, "series", f) for _, f in steps])
pv.SaveData(os.path.join(out, "pv-steps.pvd"), proxy=reader, WriteTimeSteps=1)
note("pv-steps.pvd", "paraview .pvd", "paraview.simple.SaveData")

for w in written:
    print(json.dumps(w))
