# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of the Python bindings (run by CTest: python_bindings).

They use the bundled example files (HMO_EXAMPLE_DATA_DIR): bunny_dualsheet.vtk
(2832 hexahedra, 3724 vertices, 45 inverted) and bunny_reference.obj.
"""

import hashlib
import os
import threading

import numpy as np
import pytest

import hexmesh_optimization as hmo

DATA = os.environ.get(
    "HMO_EXAMPLE_DATA_DIR",
    os.path.join(os.path.dirname(__file__), "..", "..", "examples", "Hexahedral_mesh_optimization", "data"))
BUNNY = os.path.join(DATA, "bunny_dualsheet.vtk")
REFERENCE = os.path.join(DATA, "bunny_reference.obj")


def unit_cube_grid(n=3):
    """An n x n x n grid of unit cubes, MEDIT/VTK vertex order."""
    idx = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)
    points = np.array([[i, j, k] for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)], dtype=float)
    hexes = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                hexes.append([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                              idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)])
    return points, np.array(hexes, dtype=np.int64)


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if t and t[0] == "v":
                vertices.append([float(x) for x in t[1:4]])
            elif t and t[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in t[1:]])
    return np.array(vertices), np.array(faces, dtype=np.int64)


@pytest.fixture(scope="module")
def bunny():
    return hmo.read(BUNNY)


# ------------------------------------------------------------------ reading


def test_read_gives_numpy_arrays(bunny):
    points, hexes = bunny
    assert points.dtype == np.float64 and points.shape == (3724, 3)
    assert hexes.dtype == np.int64 and hexes.shape == (2832, 8)
    assert hexes.min() == 0 and hexes.max() < len(points)


def test_read_accepts_a_path_object(bunny):
    import pathlib
    points, hexes = hmo.read(pathlib.Path(BUNNY))
    assert np.array_equal(points, bunny[0]) and np.array_equal(hexes, bunny[1])


def test_missing_file_is_file_not_found(tmp_path):
    missing = str(tmp_path / "nothing.vtk")
    with pytest.raises(FileNotFoundError, match="nothing.vtk"):
        hmo.read(missing)


def test_malformed_file_is_value_error_naming_file_and_line(tmp_path):
    bad = tmp_path / "bad.mesh"
    bad.write_text("MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n1 1 nan_here 0\nEnd\n")
    with pytest.raises(ValueError, match=r"bad\.mesh:6:"):
        hmo.read(str(bad))


def test_unknown_extension_is_value_error(tmp_path):
    f = tmp_path / "mesh.xyz"
    f.write_text("x")
    with pytest.raises(ValueError, match="extension"):
        hmo.read(str(f))


# ------------------------------------------------------------------ quality


def test_scaled_jacobian_and_quality_agree(bunny):
    sj = hmo.scaled_jacobian(*bunny)
    q = hmo.quality(*bunny)
    assert sj.shape == (2832,)
    assert q["hexes"] == 2832 and q["vertices"] == 3724
    assert q["inverted"] == int((sj < 0).sum()) == 45
    assert q["msj"] == pytest.approx(sj.min()) and q["asj"] == pytest.approx(sj.mean())
    assert q["histogram"].sum() == 2832 and len(q["histogram_edges"]) == len(q["histogram"]) + 1
    assert q["histogram_edges"][0] == -1.0 and q["histogram_edges"][-1] == 1.0
    assert q["certified_valid"] == 2832 - len(q["not_certified"])
    assert set(np.flatnonzero(sj < 0)) <= set(q["not_certified"])


def test_unit_cubes_have_scaled_jacobian_one():
    points, hexes = unit_cube_grid(2)
    assert np.allclose(hmo.scaled_jacobian(points, hexes), 1.0)
    q = hmo.quality(points, hexes)
    assert q["inverted"] == 0 and q["certified_valid"] == 8


def test_a_sheared_hex_has_the_known_scaled_jacobian():
    points, hexes = unit_cube_grid(1)
    points[4:, 0] += 1.0  # shear the top face by 45 degrees: every frame has det = 1/sqrt(2)
    assert hmo.scaled_jacobian(points, hexes)[0] == pytest.approx(1 / np.sqrt(2))


@pytest.mark.parametrize("points, hexes, message", [
    (np.zeros((4, 2)), np.zeros((1, 8), dtype=np.int64), r"points: expected an array of shape \(N, 3\)"),
    (np.zeros((8, 3)), np.zeros((1, 7), dtype=np.int64), r"hexes: expected an array of shape \(M, 8\)"),
    (np.zeros((8, 3)), np.zeros((1, 8)), "integer"),
    (np.zeros((8, 3)), np.array([[0, 1, 2, 3, 4, 5, 6, -1]]), "negative"),
    (np.zeros((8, 3)), np.array([[0, 1, 2, 3, 4, 5, 6, 8]]), "out of range"),
    (np.zeros((8, 3)), np.array([[0, 1, 2, 3, 4, 5, 6, 6]]), "repeated"),
    (np.full((8, 3), np.nan), np.array([[0, 1, 2, 3, 4, 5, 6, 7]]), "finite"),
    (np.zeros((8, 3)), np.zeros((0, 8), dtype=np.int64), "no hexahedron"),
])
def test_bad_arrays_are_value_errors(points, hexes, message):
    with pytest.raises(ValueError, match=message):
        hmo.quality(points, hexes)


# ------------------------------------------------------------------ writing


@pytest.mark.parametrize("extension", [".mesh", ".vtk", ".vtu", ".msh", ".inp", ".exo"])
def test_write_then_read_is_exact(tmp_path, bunny, extension):
    path = str(tmp_path / ("bunny" + extension))
    sj = hmo.scaled_jacobian(*bunny)
    hmo.write(path, *bunny, cell_data={"scaled_jacobian": sj})
    if extension == ".msh":  # the reader says that it drops the field
        with pytest.warns(UserWarning, match=r"skipped section \$ElementData"):
            points, hexes = hmo.read(path)
    else:
        points, hexes = hmo.read(path)
    assert np.array_equal(points, bunny[0]) and np.array_equal(hexes, bunny[1])
    if extension in (".vtu", ".msh"):
        assert "scaled_jacobian" in open(path).read()


@pytest.mark.parametrize("fmt, head", [("msh22-binary", b"$MeshFormat\n2.2 1 8\n"),
                                       ("msh41-binary", b"$MeshFormat\n4.1 1 8\n"),
                                       ("msh22", b"$MeshFormat\n2.2 0 8\n"),
                                       ("vtk-binary", b"# vtk DataFile"),
                                       ("inp", b"*HEADING")])
def test_write_in_a_chosen_format(tmp_path, bunny, fmt, head):
    path = str(tmp_path / "bunny.out")  # an extension that names no format
    hmo.write(path, *bunny, format=fmt)
    assert open(path, "rb").read(len(head)) == head
    if fmt.startswith("msh"):
        os.rename(path, path + ".msh")
        points, hexes = hmo.read(path + ".msh")
        assert np.array_equal(points, bunny[0]) and np.array_equal(hexes, bunny[1])
    with pytest.raises(ValueError, match="unknown format"):
        hmo.write(path, *bunny, format="stl")


def test_write_refuses_bad_input_and_leaves_no_file(tmp_path, bunny):
    with pytest.raises(ValueError, match="extension"):
        hmo.write(str(tmp_path / "out.xyz"), *bunny)
    with pytest.raises(ValueError, match="one number per hexahedron"):
        hmo.write(str(tmp_path / "out.vtu"), *bunny, cell_data={"q": np.zeros(3)})
    with pytest.raises(OSError):
        hmo.write(str(tmp_path / "no_such_dir" / "out.vtu"), *bunny)
    assert os.listdir(tmp_path) == []


# ------------------------------------------------------------- optimisation


def test_untangle_removes_the_inverted_elements(bunny):
    calls = []
    new_points, report = hmo.untangle(*bunny, progress=lambda stage, value: calls.append((stage, value)))
    assert new_points.shape == bunny[0].shape
    assert report["inverted_before"] == 45 and report["inverted_after"] == 0
    assert report["success"] and not report["time_limit_reached"] and not report["interrupted"]
    assert hmo.quality(new_points, bunny[1])["inverted"] == 0
    assert report["certificate"]["certified_valid"] == 2832
    assert report["stages"] and {"name", "inverted_before", "inverted_after", "msj_after", "seconds", "rounds",
                                  "details"} <= set(report["stages"][0])
    # progress: (stage name, count of elements to fix) and (stage name, 1.0) when a stage is done
    assert calls and all(isinstance(s, str) for s, _ in calls)
    assert any(isinstance(v, int) for _, v in calls) and any(v == 1.0 and isinstance(v, float) for _, v in calls)
    assert {s["name"] for s in report["stages"]} <= {s for s, _ in calls}


def digest(a):
    return hashlib.sha256(np.ascontiguousarray(a).tobytes()).hexdigest()


def test_optimize_is_deterministic_and_thread_independent(bunny):
    p1, r1 = hmo.optimize(*bunny, threads=1)
    p2, r2 = hmo.optimize(*bunny, threads=2)
    p3, _ = hmo.optimize(*bunny)
    assert digest(p1) == digest(p2) == digest(p3)
    assert r1["inverted_after"] == 0 and r1["msj_after"] > r1["msj_before"]
    assert r1["msj_after"] == r2["msj_after"]
    assert r1["surface_error"] <= 0.02


def test_reference_as_path_or_arrays_gives_the_same_result(bunny):
    vertices, faces = read_obj(REFERENCE)
    pa, ra = hmo.untangle(*bunny, reference=REFERENCE)
    pb, rb = hmo.untangle(*bunny, reference=(vertices, faces))
    assert ra["inverted_after"] == 0
    assert digest(pa) == digest(pb)


def test_reference_errors():
    points, hexes = unit_cube_grid(2)
    with pytest.raises(FileNotFoundError):
        hmo.untangle(points, hexes, reference="/nonexistent/ref.obj")
    with pytest.raises(ValueError, match="face 0 uses vertex 9"):
        hmo.untangle(points, hexes, reference=(np.zeros((3, 3)), np.array([[0, 1, 9]])))
    # a reference of another object, far away: refused before anything moves
    far = (np.array([[100., 100, 100], [101, 100, 100], [100, 101, 100], [100, 100, 101]]),
           np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    with pytest.raises(ValueError, match="reference surface"):
        hmo.untangle(points, hexes, reference=far)


def test_options_are_checked():
    points, hexes = unit_cube_grid(2)
    with pytest.raises(TypeError, match="unexpected keyword argument 'target_msj'"):
        hmo.untangle(points, hexes, target_msj=0.5)  # a quality option
    with pytest.raises(TypeError, match="unexpected keyword argument 'crease_seed_angle'"):
        hmo.untangle(points, hexes, crease_seed_angle=150)  # a quality option too
    with pytest.raises(ValueError, match="crease_seed_angle"):
        hmo.optimize(points, hexes, crease_seed_angle=200)
    with pytest.raises(TypeError, match="unexpected keyword argument 'turn_focus_band'"):
        hmo.untangle(points, hexes, turn_focus_band=0.2)  # a quality option
    with pytest.raises(ValueError, match="turn_focus_band"):
        hmo.optimize(points, hexes, turn_focus_band=0)
    with pytest.raises(ValueError, match="turn_focus_band"):
        hmo.improve_quality(points, hexes, turn_focus_band=1.5)
    with pytest.raises(ValueError, match="reference_feature_angle"):
        hmo.untangle(points, hexes, reference_feature_angle=-1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'no_such_option'"):
        hmo.optimize(points, hexes, no_such_option=1)
    with pytest.raises(ValueError, match="method"):
        hmo.optimize(points, hexes, method="fast")
    with pytest.raises(ValueError, match="surface_tolerance"):
        hmo.optimize(points, hexes, surface_tolerance=-1)
    with pytest.raises(TypeError, match="pull_back"):
        hmo.optimize(points, hexes, pull_back="yes")
    with pytest.raises(TypeError, match="coarse_level_start"):
        hmo.optimize(points, hexes, coarse_level_start="yes")
    with pytest.raises(TypeError, match="unexpected keyword argument 'coarse_level_start'"):
        hmo.untangle(points, hexes, coarse_level_start=False)
    with pytest.raises(TypeError, match="progress"):
        hmo.optimize(points, hexes, progress=3)


def test_local_surface_tolerance_and_the_off_surface_report():
    # a graded wall grid (first layer 1e-3, growth 1.3), one vertex pushed below the first layer
    n, layers = 6, 5
    z = [0.0]
    for k in range(layers):
        z.append(z[-1] + 1e-3 * 1.3 ** k)
    points, hexes = unit_cube_grid(n)
    idx = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)
    points = np.array([[i / n, j / n, z[k]] for k in range(layers + 1) for j in range(n + 1) for i in range(n + 1)])
    hexes = hexes[: n * n * layers]
    points[idx(3, 3, 2), 2] = 0.5 * z[1]
    assert hmo.quality(points, hexes)["inverted"] > 0
    new_points, report = hmo.optimize(points, hexes, local_surface_tolerance=0.01)
    assert report["inverted_after"] == 0
    assert report["off_surface"] == []
    assert np.abs(new_points[: (n + 1) ** 2, 2]).max() <= 0.01 * z[1]
    # with none, a tangled mesh that must move its boundary reports the vertices left off, farthest first
    _, report = hmo.untangle(*hmo.read(BUNNY), local_surface_tolerance=0.0)
    off = report["off_surface"]
    assert off and set(off[0]) == {"vertex", "distance", "allowed", "local_length"}
    assert all(o["distance"] > o["allowed"] for o in off)
    assert any("farther from the reference surface" in w for w in report["warnings"])
    with pytest.raises(ValueError, match="local_surface_tolerance"):
        hmo.optimize(points, hexes, local_surface_tolerance=float("nan"))


def test_a_valid_mesh_is_never_made_worse():
    points, hexes = unit_cube_grid(3)
    new_points, report = hmo.improve_quality(points, hexes, target_msj=0.9, method="paper")
    assert report["msj_after"] >= report["msj_before"] == pytest.approx(1.0)
    assert hmo.quality(new_points, hexes)["inverted"] == 0


def test_time_limit_is_a_hard_stop(bunny):
    new_points, report = hmo.optimize(*bunny, time_limit=1e-6)
    assert report["time_limit_reached"]
    q = hmo.quality(new_points, bunny[1])
    assert q["inverted"] <= 45 and report["inverted_after"] == q["inverted"]


def test_an_exception_in_progress_stops_the_run_and_is_raised(bunny):
    class Stop(Exception):
        pass

    def progress(stage, value):
        raise Stop(stage)

    with pytest.raises(Stop):
        hmo.optimize(*bunny, progress=progress)


def test_other_threads_run_while_optimising(bunny):
    # The GIL is released during the run: another Python thread keeps counting.
    # Were it held, that thread could not run at all between the call and its
    # return (the C++ code runs no bytecode, so the interpreter never hands the
    # GIL over): the count would not move during the call.
    done = threading.Event()
    count = [0]

    def counter():
        while not done.is_set():
            count[0] += 1

    t = threading.Thread(target=counter)
    t.start()
    try:
        while count[0] == 0:
            pass
        before = count[0]
        hmo.untangle(*bunny, threads=1)
        after = count[0]
    finally:
        done.set()
        t.join()
    assert after - before > 100000, (before, after)


# -------------------------------------------------------------------- meshio


def test_optimize_meshio():
    meshio = pytest.importorskip("meshio")
    mesh = meshio.read(BUNNY)
    new_mesh, report = hmo.optimize_meshio(mesh, return_report=True)
    assert isinstance(new_mesh, meshio.Mesh)
    assert report["inverted_after"] == 0
    hex_blocks = [b for b in new_mesh.cells if b.type == "hexahedron"]
    assert len(hex_blocks) == 1 and np.array_equal(hex_blocks[0].data, mesh.cells_dict["hexahedron"])
    sj = new_mesh.cell_data["scaled_jacobian"][0]
    assert sj.shape == (2832,) and sj.min() > 0
    assert np.allclose(sj, hmo.scaled_jacobian(new_mesh.points, hex_blocks[0].data))
    assert not np.array_equal(new_mesh.points, mesh.points)
    assert mesh.points.shape == new_mesh.points.shape
    # the input is untouched
    assert np.array_equal(mesh.points, meshio.read(BUNNY).points)


def test_optimize_meshio_without_hexahedra():
    meshio = pytest.importorskip("meshio")
    mesh = meshio.Mesh(np.eye(3), [("triangle", np.array([[0, 1, 2]]))])
    with pytest.raises(ValueError, match="no hexahedron"):
        hmo.optimize_meshio(mesh)
