"""Renders the RHS sub-model mesh (docs/fe.md) with gnuplot from a .vtu file that flexstress wrote.

The file comes from the FE tests: `./build/tests/flexstress_test_fe -tc="VTK: the RHS*"` writes
build/tests/output/rhs_attachment_bending.vtu (default mesh, 1792 bricks, pure bending with
100 MPa nominal tension on the top flange). VTK (python3-vtk9) reads it and extracts the
boundary faces; gnuplot (gnuplot-nox, pngcairo) draws them as polygons in depth order, coloured
by the averaged nodal von Mises stress, since VTK's own renderer needs an X server.

Usage: python3 docs/render_rhs_mesh.py [build/tests/output/rhs_attachment_bending.vtu]
Writes docs/rhs_attachment_mesh.png (whole segment) and docs/rhs_attachment_weld.png (close-up).
"""
import os
import subprocess
import sys
import tempfile

from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

here = os.path.dirname(os.path.abspath(__file__))
vtu = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    here, "..", "build", "tests", "output", "rhs_attachment_bending.vtu")

reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(vtu)
reader.Update()
surface = vtkDataSetSurfaceFilter()
surface.SetInputConnection(reader.GetOutputPort())
surface.Update()
poly = surface.GetOutput()
vm = poly.GetPointData().GetArray("von_mises")


STOPS = [(0.0, (0, 0, 255)), (0.25, (0, 255, 255)), (0.5, (0, 255, 0)),
         (0.75, (255, 255, 0)), (1.0, (255, 0, 0))]
VMAX = max(vm.GetValue(i) for i in range(vm.GetNumberOfTuples())) / 1e6
BINS = 24  # gnuplot 5.4 colours polygons per plot, so faces are grouped into colour bins


def colour(f):
    """'#rrggbb' at fraction f of the scale, piecewise linear like the palette below."""
    for (f0, c0), (f1, c1) in zip(STOPS, STOPS[1:]):
        if f <= f1:
            w = (f - f0) / (f1 - f0)
            return "#%02x%02x%02x" % tuple(round(a + w * (b - a)) for a, b in zip(c0, c1))
    return "#ff0000"


def polygons(path, xmin=-1e9, xmax=1e9, ymin=-1e9):
    """Boundary faces as polygons (x, z, y: y up in gnuplot's z), grouped by von Mises bin
    (one data block per bin, separated by two blank lines). Returns the bins present."""
    groups = {}
    for c in range(poly.GetNumberOfCells()):
        ids = poly.GetCell(c).GetPointIds()
        pts = [poly.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
        if min(p[0] for p in pts) < xmin or max(p[0] for p in pts) > xmax:
            continue
        if min(p[1] for p in pts) < ymin:
            continue
        s = sum(vm.GetValue(ids.GetId(k)) for k in range(ids.GetNumberOfIds())) / len(pts) / 1e6
        b = min(int(s / VMAX * BINS), BINS - 1)
        groups.setdefault(b, []).append(pts)
    present = sorted(groups)
    with open(path, "w") as out:
        for b in present:
            for pts in groups[b]:
                for p in pts:
                    out.write("%.9g %.9g %.9g\n" % (p[0], p[2], p[1]))
                out.write("\n")
            out.write("\n")
    return present


def plot(data, bins, png, title, view, xrange):
    terms = ", ".join(f"'{data}' index {i} with polygons fc rgb '{colour((b + 0.5) / BINS)}'"
                      for i, b in enumerate(bins))
    script = f"""
set terminal pngcairo size 1400,900 font 'DejaVu Sans,12'
set output '{png}'
set title "{title}"
set view {view}
set view equal xyz
set xyplane 0
set xrange [{xrange}]
set xlabel 'x [m]'
set ylabel 'z [m]'
set zlabel 'y [m]' rotate
set pm3d depthorder border lc rgb '#202020' lw 0.5
set palette defined (0 'blue', 0.25 'cyan', 0.5 'green', 0.75 'yellow', 1 'red')
set cbrange [0:{VMAX}]
set colorbox
set cblabel 'von Mises [MPa] (pure bending, 100 MPa nominal)'
unset key
splot {terms}, '{data}' index 0 every ::0::0 using 1:2:3:(0) with points pt 7 ps 0 lc palette
"""
    subprocess.run(["gnuplot"], input=script.encode(), check=True)


with tempfile.TemporaryDirectory() as tmp:
    full = os.path.join(tmp, "full.dat")
    weld = os.path.join(tmp, "weld.dat")
    full_bins = polygons(full)
    weld_bins = polygons(weld, 0.605, 0.695, 0.04)
    plot(full, full_bins, os.path.join(here, "rhs_attachment_mesh.png"),
         "RHS 150x100x4 segment with welded rib (density 1: 1792 hex8)", "62, 28, 1.3", "0.5:0.8")
    plot(weld, weld_bins, os.path.join(here, "rhs_attachment_weld.png"),
         "Rib and fillet welds: weld toes at x = 0.63 and 0.67 m", "55, 25, 1.4", "0.605:0.695")
print("wrote", os.path.join(here, "rhs_attachment_mesh.png"), "and rhs_attachment_weld.png")
