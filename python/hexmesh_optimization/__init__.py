# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Untangling and quality improvement of hexahedral meshes, on numpy arrays.

The Python face of the CGAL package Hexahedral_mesh_optimization. A mesh is a
pair of arrays: ``points`` (float64, N x 3) and ``hexes`` (integers, M x 8,
MEDIT/VTK vertex order: 0-3 the bottom face, i + 4 above i; numbered from 0).

    import hexmesh_optimization as hmo
    points, hexes = hmo.read("bunny_dualsheet.vtk")
    new_points, report = hmo.optimize(points, hexes)
    print(report["inverted_after"], report["msj_after"])
    hmo.write("bunny.vtu", new_points, hexes,
              cell_data={"scaled_jacobian": hmo.scaled_jacobian(new_points, hexes)})

Functions: read, write, scaled_jacobian, quality, untangle, improve_quality,
optimize (compiled), and optimize_meshio (meshio interoperability; meshio is
imported only when it is called). See each function's docstring.
"""

from ._hexmesh_optimization import (  # noqa: F401
    read,
    write,
    scaled_jacobian,
    quality,
    untangle,
    improve_quality,
    optimize,
)

__all__ = ["read", "write", "scaled_jacobian", "quality", "untangle", "improve_quality", "optimize",
           "optimize_meshio"]

_HEX_TYPES = ("hexahedron",)


def optimize_meshio(mesh, reference=None, progress=None, function="optimize", return_report=False, **options):
    """Optimises the hexahedra of a ``meshio.Mesh``; returns a new ``meshio.Mesh``.

    The hexahedron cell blocks are optimised together (``optimize``, or
    ``untangle`` / ``improve_quality`` with ``function=``); the other blocks,
    the point data, cell sets and field data are carried over unchanged (the
    connectivity never changes, only the points move). The new mesh has a
    ``scaled_jacobian`` cell field: the value of each hexahedron, NaN for the
    cells of other types. ``reference``, ``progress`` and the options are
    those of :func:`optimize`. Returns the new mesh, or ``(new_mesh,
    report)`` with ``return_report=True`` (the report of :func:`optimize`).

    Raises ValueError when the mesh has no hexahedron.
    """
    import numpy as np
    import meshio

    functions = {"optimize": optimize, "untangle": untangle, "improve_quality": improve_quality}
    if function not in functions:
        raise ValueError("function: expected one of %s, got %r" % (sorted(functions), function))
    blocks = [b for b in mesh.cells if b.type in _HEX_TYPES]
    if not blocks:
        types = sorted({b.type for b in mesh.cells})
        raise ValueError("the mesh has no hexahedron cell block (cell types: %s)" % (", ".join(types) or "none"))
    hexes = np.concatenate([np.asarray(b.data, dtype=np.int64) for b in blocks])
    points = np.ascontiguousarray(np.asarray(mesh.points, dtype=np.float64)[:, :3])
    new_points, report = functions[function](points, hexes, reference=reference, progress=progress, **options)
    sj = scaled_jacobian(new_points, hexes)

    cell_data = {name: [np.copy(a) for a in arrays] for name, arrays in mesh.cell_data.items()}
    per_block, offset = [], 0
    for b in mesh.cells:
        if b.type in _HEX_TYPES:
            per_block.append(sj[offset:offset + len(b.data)])
            offset += len(b.data)
        else:
            per_block.append(np.full(len(b.data), np.nan))
    cell_data["scaled_jacobian"] = per_block
    out_points = np.array(mesh.points, dtype=np.float64, copy=True)
    out_points[:, :3] = new_points
    new_mesh = meshio.Mesh(
        out_points,
        [meshio.CellBlock(b.type, np.copy(b.data)) for b in mesh.cells],
        point_data={k: np.copy(v) for k, v in mesh.point_data.items()},
        cell_data=cell_data,
        field_data=dict(mesh.field_data),
        point_sets={k: np.copy(v) for k, v in mesh.point_sets.items()},
        cell_sets={k: [np.copy(a) for a in v] for k, v in mesh.cell_sets.items()},
    )
    return (new_mesh, report) if return_report else new_mesh
