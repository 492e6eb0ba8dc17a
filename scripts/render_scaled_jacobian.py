#!/usr/bin/python3
# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Renders a hexahedral mesh coloured by the scaled Jacobian of its elements.

    render_scaled_jacobian.py MESH OUT.png [--title TEXT] [--size W H]

The mesh is read and its scaled Jacobians computed by the package's Python
bindings (hexmesh_optimization, on PYTHONPATH); VTK (Debian: python3-vtk9)
draws it offscreen. To show the interior, the half of the mesh beyond the
plane through its centre, normal to the bounding box's longest axis, is cut
away, whole elements at a time. Red: inverted (scaled Jacobian < 0); then
yellow, green and blue up to 1. The view depends only on the mesh's bounding
box, so two meshes of the same object (before and after an optimisation)
are seen from the same place.

VTK's X11 build needs a display: run it under `xvfb-run -a` on a headless
machine (the documentation build, doc/build_manual.cmake, does).
"""

import argparse
import sys

import numpy as np


def unstructured_grid(vtk, points, hexes, sj):
    from vtk.util import numpy_support as ns
    grid = vtk.vtkUnstructuredGrid()
    vp = vtk.vtkPoints()
    vp.SetData(ns.numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    grid.SetPoints(vp)
    cells = np.hstack([np.full((len(hexes), 1), 8, dtype=np.int64), hexes.astype(np.int64)]).ravel()
    ca = vtk.vtkCellArray()
    ca.SetCells(len(hexes), ns.numpy_to_vtkIdTypeArray(cells, deep=True))
    grid.SetCells(vtk.VTK_HEXAHEDRON, ca)
    values = ns.numpy_to_vtk(np.ascontiguousarray(sj, dtype=np.float64), deep=True)
    values.SetName("scaled_jacobian")
    grid.GetCellData().SetScalars(values)
    return grid


def lookup_table(vtk):
    """-1..0 red, 0..1 yellow -> green -> blue."""
    ctf = vtk.vtkColorTransferFunction()
    ctf.AddRGBPoint(-1.0, 0.55, 0.0, 0.0)
    ctf.AddRGBPoint(-1e-9, 0.95, 0.1, 0.1)
    ctf.AddRGBPoint(0.0, 1.0, 0.85, 0.1)
    ctf.AddRGBPoint(0.5, 0.3, 0.75, 0.3)
    ctf.AddRGBPoint(1.0, 0.15, 0.35, 0.8)
    lut = vtk.vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    lut.SetRange(-1.0, 1.0)
    for i in range(256):
        r, g, b = ctf.GetColor(-1.0 + 2.0 * i / 255.0)
        lut.SetTableValue(i, r, g, b, 1.0)
    lut.Build()
    return lut


def render(mesh_path, png_path, title, size):
    import vtk
    import hexmesh_optimization as hmo

    points, hexes = hmo.read(mesh_path)
    sj = hmo.scaled_jacobian(points, hexes)
    grid = unstructured_grid(vtk, points, hexes, sj)

    lo, hi = points.min(axis=0), points.max(axis=0)
    centre = 0.5 * (lo + hi)
    axis = int(np.argmax(hi - lo))
    normal = [0.0, 0.0, 0.0]
    normal[axis] = 1.0
    plane = vtk.vtkPlane()
    plane.SetOrigin(*centre)
    plane.SetNormal(*normal)
    cut = vtk.vtkExtractGeometry()  # whole elements on the kept side
    cut.SetInputData(grid)
    cut.SetImplicitFunction(plane)
    cut.ExtractInsideOn()
    cut.ExtractBoundaryCellsOn()
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputConnection(cut.GetOutputPort())

    lut = lookup_table(vtk)
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    mapper.SetLookupTable(lut)
    mapper.SetScalarModeToUseCellData()
    mapper.SetScalarRange(-1.0, 1.0)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().EdgeVisibilityOn()
    actor.GetProperty().SetEdgeColor(0.15, 0.15, 0.15)
    actor.GetProperty().SetLineWidth(0.5)

    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle("scaled Jacobian")
    bar.SetNumberOfLabels(5)
    bar.SetWidth(0.1)
    bar.SetHeight(0.6)
    bar.SetPosition(0.87, 0.2)
    for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        prop.SetColor(0.1, 0.1, 0.1)
        prop.ShadowOff()
        prop.ItalicOff()

    text = vtk.vtkTextActor()
    inverted = int((sj < 0).sum())
    text.SetInput("%s\n%d hexahedra, %d inverted, MSJ %.3f, ASJ %.3f"
                  % (title, len(hexes), inverted, sj.min(), sj.mean()))
    text.GetTextProperty().SetFontSize(18)
    text.GetTextProperty().SetColor(0.1, 0.1, 0.1)
    text.SetPosition(12, size[1] - 60)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(actor)
    renderer.AddActor2D(bar)
    renderer.AddActor2D(text)
    camera = renderer.GetActiveCamera()
    # look at the cut face, from a little aside and above
    # (y up, as most scanned models are, unless y is the cut's normal)
    up = np.array([0.0, 1.0, 0.0]) if axis != 1 else np.array([0.0, 0.0, 1.0])
    side = np.cross(up, normal)
    direction = np.array(normal) + 0.5 * side + 0.35 * up
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*(centre + direction * np.linalg.norm(hi - lo)))
    camera.SetViewUp(*up)
    renderer.ResetCamera()
    camera.Zoom(1.1)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*size)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(png_path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("mesh")
    p.add_argument("png")
    p.add_argument("--title", default="")
    p.add_argument("--size", nargs=2, type=int, default=[900, 650], metavar=("W", "H"))
    a = p.parse_args(argv)
    try:
        render(a.mesh, a.png, a.title or a.mesh, a.size)
    except (OSError, ValueError) as e:
        print("render_scaled_jacobian: error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
