"""Reads a .vtu file with the real VTK library and dumps it as plain text for the C++ tests.

Usage: read_vtu.py INPUT.vtu OUTPUT.txt
Output lines (whitespace separated, floats in repr form so they round-trip exactly):
  points N
  cells M
  types t_0 ... t_{M-1}
  connectivity <ids of cell 0> | <ids of cell 1> | ...   (flattened, with cell sizes first)
  coords x_0 y_0 z_0 x_1 ...
  point NAME NCOMP v...     (one line per point-data array)
  cell NAME NCOMP v...      (one line per cell-data array)
Exit codes: 0 success, 3 VTK is not importable (install python3-vtk9), 4 the file did not read.
"""
import sys

try:
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError:  # older layouts
    try:
        from vtk import vtkXMLUnstructuredGridReader
    except ImportError:
        sys.stderr.write("python3 cannot import vtk: install python3-vtk9\n")
        sys.exit(3)


def main():
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(sys.argv[1])
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or reader.GetErrorCode() != 0:
        sys.exit(4)
    lines = []
    n = grid.GetNumberOfPoints()
    m = grid.GetNumberOfCells()
    lines.append("points %d" % n)
    lines.append("cells %d" % m)
    lines.append("types " + " ".join(str(grid.GetCellType(i)) for i in range(m)))
    conn = []
    for i in range(m):
        ids = grid.GetCell(i).GetPointIds()
        conn.append(str(ids.GetNumberOfIds()))
        conn.extend(str(ids.GetId(k)) for k in range(ids.GetNumberOfIds()))
    lines.append("connectivity " + " ".join(conn))
    coords = []
    for i in range(n):
        coords.extend(repr(float(v)) for v in grid.GetPoint(i))
    lines.append("coords " + " ".join(coords))
    for kind, data in (("point", grid.GetPointData()), ("cell", grid.GetCellData())):
        for a in range(data.GetNumberOfArrays()):
            arr = data.GetArray(a)
            nc = arr.GetNumberOfComponents()
            values = [repr(float(arr.GetComponent(t, c)))
                      for t in range(arr.GetNumberOfTuples()) for c in range(nc)]
            lines.append("%s %s %d %s" % (kind, arr.GetName(), nc, " ".join(values)))
    with open(sys.argv[2], "w") as out:
        out.write("\n".join(lines) + "\n")


main()
