#!/usr/bin/python3
# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Our simulation-format files against readers and writers nobody here wrote:
#  (a) meshio reads every file we write (gmsh 4.1 and 2.2, ASCII and binary;
#      Abaqus; Exodus II when the build has it) with the same points, the same
#      hexahedra and the groups meshio exposes;
#  (b) we read what meshio writes in each of these formats, with the same
#      points, hexahedra and the groups meshio writes;
#  (c) gmsh opens our .msh files (and we read what gmsh writes back);
#  (d) meshio (gmsh for .msh) reads every file of the conversion matrix of
#      test_hex_mesh_io (--write-matrix DIR): each reader x each writer.
# usage: test_foreign_readers.py PROBE... WORKDIR
#   PROBE...: the command of the test program test_hex_mesh_io (hmo_tests
#   test_hex_mesh_io), whose --write-samples DIR writes our files and
#   --dump FILE prints what we read as JSON.
# Exit 77 (skipped) when meshio is missing; the gmsh part is skipped (with a
# message) when gmsh is absent.

import json
import os
import shutil
import subprocess
import sys

try:
    import meshio
    import numpy as np
except ImportError as e:
    print("skipped: meshio is missing (Debian python3-meshio):", e)
    sys.exit(77)

probe, work = sys.argv[1:-1], sys.argv[-1]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

failures = []
rows = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)
    return condition


def dump(path):
    """the mesh as we read it, or None"""
    r = subprocess.run(probe + ["--dump", path], capture_output=True, text=True)
    if not check(r.returncode == 0, "we cannot read %s: %s" % (path, r.stderr.strip())):
        return None
    return json.loads(r.stdout)


def hexahedra(mesh):
    blocks = [c.data for c in mesh.cells if c.type == "hexahedron"]
    return np.concatenate(blocks) if blocks else np.zeros((0, 8), dtype=int)


def cell_values(mesh, key):
    if key not in mesh.cell_data:
        return None
    return np.concatenate([v for v, c in zip(mesh.cell_data[key], mesh.cells) if c.type == "hexahedron"])


subprocess.run(probe + ["--write-samples", work], check=True)
with open(os.path.join(work, "expected.json")) as f:
    expected = json.load(f)
with open(os.path.join(work, "expected_exodus.json")) as f:
    expected_exodus = json.load(f)
have_exodus = os.path.exists(os.path.join(work, "ours.exo"))

# ------------------------------------------------------------ (a) meshio reads ours
ours = ["ours_41_ascii.msh", "ours_41_binary.msh", "ours_22_ascii.msh", "ours_22_binary.msh", "ours.inp"]
if have_exodus:
    ours.append("ours.exo")
for name in ours:
    e = expected_exodus if name.endswith(".exo") else expected
    points = np.array(e["points"])
    hexes = np.array(e["hexahedra"])
    try:
        m = meshio.read(os.path.join(work, name))
    except BaseException as ex:  # meshio raises many kinds
        check(False, "meshio cannot read our %s: %s" % (name, ex))
        rows.append((name, "no", "-", "-"))
        continue
    same = check(np.array_equal(m.points, points), "%s: meshio reads other points" % name)
    same = check(np.array_equal(hexahedra(m), hexes), "%s: meshio reads other hexahedra" % name) and same
    groups = []
    if name.endswith(".msh"):
        physical = cell_values(m, "gmsh:physical")
        if check(physical is not None and list(physical) == e["references"],
                 "%s: physical tags %s, expected %s" % (name, physical, e["references"])):
            groups.append("physical tags")
        jacobian = cell_values(m, "scaled_jacobian")
        if check(jacobian is not None and list(jacobian) == list(range(len(hexes))),
                 "%s: $ElementData scaled_jacobian %s" % (name, jacobian)):
            groups.append("$ElementData")
    if name.endswith(".inp"):
        cell_sets = {k: sorted(np.concatenate(v).tolist()) for k, v in m.cell_sets.items()}
        if check(cell_sets == {k: sorted(v) for k, v in e["hexahedron_sets"].items()},
                 "%s: cell sets %s" % (name, cell_sets)):
            groups.append("ELSET")
        point_sets = {k: sorted(v.tolist()) for k, v in m.point_sets.items()}
        if check(point_sets == {k: sorted(v) for k, v in e["vertex_sets"].items()},
                 "%s: point sets %s" % (name, point_sets)):
            groups.append("NSET")
        groups.append("*SURFACE (not exposed by meshio)")
    if name.endswith(".exo"):
        point_sets = {k: sorted(v.tolist()) for k, v in m.point_sets.items()}
        if check(point_sets == {k: sorted(v) for k, v in e["vertex_sets"].items()},
                 "%s: node sets %s" % (name, point_sets)):
            groups.append("node sets")
        blocks = [len(c.data) for c in m.cells]
        if check(blocks == [4, 3, 1], "%s: meshio sees blocks of %s hexahedra" % (name, blocks)):
            groups.append("blocks (as cell blocks)")
    rows.append((name, "yes" if same else "differs", "-", ", ".join(groups) or "-"))

# ------------------------------------------------------------ (b) we read meshio's
points = np.array(expected_exodus["points"])
hexes = np.array(expected_exodus["hexahedra"])
references = np.array(expected_exodus["references"])
cell_data = {"gmsh:physical": [references], "gmsh:geometrical": [references]}
theirs = [
    ("meshio_22_ascii.msh", dict(file_format="gmsh22", binary=False), "msh"),
    ("meshio_22_binary.msh", dict(file_format="gmsh22", binary=True), "msh"),
    ("meshio_41_ascii.msh", dict(file_format="gmsh", binary=False), "msh"),
    ("meshio_41_binary.msh", dict(file_format="gmsh", binary=True), "msh"),
    ("meshio.inp", dict(file_format="abaqus"), "inp"),
    ("meshio.exo", dict(file_format="exodus"), "exo"),
]
for name, options, kind in theirs:
    if kind == "exo" and not have_exodus:
        rows.append((name, "-", "skipped (no Exodus II in this build)", "-"))
        continue
    if kind == "msh":
        m = meshio.Mesh(points, [("hexahedron", hexes)], cell_data=cell_data)
    elif kind == "inp":
        m = meshio.Mesh(points, [("hexahedron", hexes)],
                        cell_sets={k: [np.array(v)] for k, v in expected_exodus["hexahedron_sets"].items()},
                        point_sets={k: np.array(v) for k, v in expected_exodus["vertex_sets"].items()})
    else:
        m = meshio.Mesh(points, [("hexahedron", hexes)],
                        point_sets={k: np.array(v) for k, v in expected_exodus["vertex_sets"].items()})
    path = os.path.join(work, name)
    meshio.write(path, m, **options)
    r = dump(path)
    if r is None:
        rows.append((name, "-", "no", "-"))
        continue
    same = check(np.array_equal(np.array(r["points"]), points), "%s: we read other points" % name)
    same = check(np.array_equal(np.array(r["hexahedra"]), hexes), "%s: we read other hexahedra" % name) and same
    groups = []
    if kind == "msh":
        if name.startswith("meshio_41"):
            # meshio's 4.1 writer has no $Entities, hence no physical tags
            check(r["references"] == [0] * len(hexes), "%s: references %s" % (name, r["references"]))
            groups.append("physical tags not written by meshio (no $Entities)")
        elif check(r["references"] == references.tolist(), "%s: references %s" % (name, r["references"])):
            groups.append("physical tags")
    if kind == "inp":
        got = {k: sorted(v) for k, v in r["hexahedron_sets"].items()}
        if check(got == {k: sorted(v) for k, v in expected_exodus["hexahedron_sets"].items()},
                 "%s: element sets %s" % (name, got)):
            groups.append("ELSET")
    if kind in ("inp", "exo"):
        got = {k: sorted(v) for k, v in r["vertex_sets"].items()}
        if check(got == {k: sorted(v) for k, v in expected_exodus["vertex_sets"].items()},
                 "%s: node sets %s" % (name, got)):
            groups.append("NSET" if kind == "inp" else "node sets")
    rows.append((name, "-", "yes" if same else "differs", ", ".join(groups) or "-"))

# an Exodus file with a block of boundary quadrangles before the hexahedra:
# the block is skipped with a warning, the hexahedra keep their ids
if have_exodus:
    quads = np.array([h[[0, 3, 2, 1]] for h in hexes[:3]])
    path = os.path.join(work, "meshio_mixed.exo")
    meshio.write(path, meshio.Mesh(points, [("quad", quads), ("hexahedron", hexes)]))
    r = dump(path)
    if r is not None:
        check(np.array_equal(np.array(r["hexahedra"]), hexes) and
              [w for w in r["warnings"] if "skipped element block" in w and "QUAD4" in w] != [],
              "meshio_mixed.exo: %d hexahedra, warnings %s" % (len(r["hexahedra"]), r["warnings"]))
        rows.append(("meshio_mixed.exo", "-", "yes (QUAD4 block skipped)", "-"))

# ------------------------------------------------------------ (c) gmsh opens ours
gmsh = shutil.which("gmsh")
gmsh_result = "skipped: gmsh is not installed (Debian gmsh)"
if gmsh:
    opened = []
    for name in [n for n in ours if n.endswith(".msh")]:
        out = os.path.join(work, "gmsh_" + name)
        r = subprocess.run([gmsh, os.path.join(work, name), "-0", "-format", "msh41", "-o", out],
                           capture_output=True, text=True)
        log = r.stdout + r.stderr
        errors = [l for l in log.splitlines() if l.startswith("Error") or l.startswith("Warning")]
        if not check(r.returncode == 0 and not errors and os.path.exists(out),
                     "gmsh on %s: exit %d, %s" % (name, r.returncode, errors)):
            continue
        back = dump(out)
        if back is None:
            continue
        # gmsh writes coordinates with 16 significant digits (equal to 1e-15)
        # and may renumber the nodes: the hexahedra are compared by their corners
        def corners(mesh):
            p = np.array(mesh["points"])
            return np.array(sorted(tuple(np.round(x, 12)) for h in mesh["hexahedra"] for x in p[h]))
        if check(len(back["hexahedra"]) == len(expected["hexahedra"]) and
                 np.allclose(corners(back), corners(expected), rtol=1e-15, atol=1e-16) and
                 sorted(back["references"]) == sorted(expected["references"]) and
                 back["reference_names"] == expected["reference_names"],
                 "gmsh's rewrite of %s differs from what we wrote" % name):
            opened.append(name)
    # a box meshed by gmsh itself (extruded, recombined: 3x2x4 hexahedra with
    # their boundary quadrangles), saved in the 4 variants (and with every
    # element, and with parametric coordinates): we read the hexahedra, the
    # physical volume and its name, and skip the rest with one warning a type
    geo = os.path.join(work, "box.geo")
    with open(geo, "w") as f:
        f.write('Point(1) = {0, 0, 0, 1.0};\n'
                'l[] = Extrude {1, 0, 0} { Point{1}; Layers{3}; Recombine; };\n'
                's[] = Extrude {0, 1, 0} { Line{l[1]}; Layers{2}; Recombine; };\n'
                'v[] = Extrude {0, 0, 1} { Surface{s[1]}; Layers{4}; Recombine; };\n'
                'Physical Volume("block", 7) = {v[1]};\nPhysical Surface("bottom", 3) = {s[1]};\n')
    meshed = []
    for variant, options, skipped_types in [
            ("msh41", ["-format", "msh41"], 1), ("msh41_binary", ["-format", "msh41", "-bin"], 1),
            ("msh22", ["-format", "msh22"], 1), ("msh22_binary", ["-format", "msh22", "-bin"], 1),
            ("msh41_all", ["-format", "msh41", "-save_all"], 3),
            ("msh41_parametric", ["-format", "msh41", "-setnumber", "Mesh.SaveParametric", "1"], 1)]:
        out = os.path.join(work, "gmsh_box_%s.msh" % variant)
        r = subprocess.run([gmsh, geo, "-3", "-o", out] + options, capture_output=True, text=True)
        if not check(r.returncode == 0, "gmsh cannot mesh the box (%s): %s" % (variant, r.stderr)):
            continue
        box = dump(out)
        if box is None:
            continue
        skips = [w for w in box["warnings"] if w.startswith("skipped")]
        if check(len(box["hexahedra"]) == 24 and len(box["points"]) == 60 and box["references"] == [7] * 24 and
                 box["reference_names"] == {"7": "block"} and len(skips) == skipped_types,
                 "gmsh's box (%s): %d hexahedra, %d points, references %s, names %s, warnings %s" % (
                     variant, len(box["hexahedra"]), len(box["points"]), sorted(set(box["references"])),
                     box["reference_names"], box["warnings"])):
            meshed.append(variant)
    gmsh_result = ("gmsh %s opens %d of 4 of our files (%s) without errors or warnings, its rewrite reads back "
                   "the same; we read %d of 6 boxes meshed by gmsh (%s)") % (
        subprocess.run([gmsh, "--version"], capture_output=True, text=True).stderr.strip() or "?",
        len(opened), ", ".join(opened), len(meshed), ", ".join(meshed))

# ------------------------------------------------------------ (d) the conversion matrix
# every file of test_hex_mesh_io's conversion matrix (each reader x each
# writer, on its generated meshes and on the shared ones present): meshio
# reads it (gmsh the .msh files) with the same points and hexahedra, and for
# the generated meshes the groups meshio exposes (MEDIT references, Abaqus
# sets, Exodus node sets; gmsh's physical tags)
matrix_dir = os.path.join(work, "matrix")
os.makedirs(matrix_dir)
r = subprocess.run(probe + ["--write-matrix", matrix_dir], capture_output=True, text=True)
print(r.stdout.strip())
matrix_result = "conversion matrix: not run"
if check(r.returncode == 0, "the conversion matrix failed: %s" % (r.stdout + r.stderr)[-2000:]):
    with open(os.path.join(matrix_dir, "matrix.json")) as f:
        entries = json.load(f)
    sources = {}
    for entry in entries:
        if entry["mesh"] not in sources:
            with open(os.path.join(matrix_dir, entry["mesh"] + ".json")) as f:
                src = json.load(f)
            sources[entry["mesh"]] = (np.array(src["points"]), np.array(src["hexahedra"]))
    counts = {"meshio": 0, "gmsh": 0, "groups": 0, "passed": 0}

    def corners(p, h):
        """the hexahedra by the coordinates of their corners (gmsh may renumber the nodes)"""
        return np.array(sorted(tuple(x) for x in p[h].reshape(-1, 8 * 3)))

    # meshio reads the files of the other formats
    msh_entries = []
    for entry in entries:
        name = os.path.basename(entry["file"])
        if name.endswith(".msh"):
            msh_entries.append(entry)
            continue
        points, hexes = sources[entry["mesh"]]
        holds = entry.get("holds")
        try:
            m = meshio.read(entry["file"])
        except BaseException as ex:  # meshio raises many kinds
            check(False, "meshio cannot read %s: %s" % (name, ex))
            continue
        got = hexahedra(m)
        ok = check(np.array_equal(m.points, points), "%s: meshio reads other points" % name)
        if "exo" in (entry["reader"], entry["writer"]):  # Exodus: block by block, compared as sets of rows
            ok = check(sorted(map(tuple, got.tolist())) == sorted(map(tuple, hexes.tolist())),
                       "%s: meshio reads other hexahedra" % name) and ok
        else:
            ok = check(np.array_equal(got, hexes), "%s: meshio reads other hexahedra" % name) and ok
        counts["meshio"] += 1
        if holds is not None and name.endswith(".mesh"):
            ref = cell_values(m, "medit:ref")
            ok = check(ref is not None and ref.tolist() == holds["references"],
                       "%s: meshio reads references %s, expected %s" % (name, ref, holds["references"])) and ok
            counts["groups"] += 1
        if holds is not None and (name.endswith(".inp") or name.endswith(".exo")):
            point_sets = {k: sorted(v.tolist()) for k, v in m.point_sets.items()}
            ok = check(point_sets == {k: sorted(v) for k, v in holds["vertex_sets"].items()},
                       "%s: meshio reads node sets %s" % (name, point_sets)) and ok
            if name.endswith(".inp"):
                cell_sets = {k: sorted(np.concatenate(v).tolist()) for k, v in m.cell_sets.items()}
                ok = check(cell_sets == {k: sorted(v) for k, v in holds["hexahedron_sets"].items()},
                           "%s: meshio reads element sets %s" % (name, cell_sets)) and ok
            counts["groups"] += 1
        counts["passed"] += 1 if ok else 0

    # gmsh reads the .msh files, in one run (a script merging and saving
    # each as 2.2 ASCII, which meshio then reads): it keeps the hexahedra of
    # the physical volumes, those of a positive reference (all when there is
    # none), with their physical tags
    if gmsh and msh_entries:
        script = os.path.join(matrix_dir, "gmsh_reads.geo")
        with open(script, "w") as f:
            f.write("Mesh.Format = 1;\nMesh.MshFileVersion = 2.2;\n")
            for i, entry in enumerate(msh_entries):
                f.write('Merge "%s";\nSave "%s";\nDelete Model;\n' % (entry["file"], os.path.join(matrix_dir, "gmsh_%d.msh" % i)))
        g = subprocess.run([gmsh, script, "-0"], capture_output=True, text=True)
        errors = [l for l in (g.stdout + g.stderr).splitlines() if l.startswith("Error")]
        check(g.returncode == 0 and not errors, "gmsh on the matrix's .msh files: exit %d, %s" % (g.returncode, errors[:5]))
        for i, entry in enumerate(msh_entries):
            name = os.path.basename(entry["file"])
            points, hexes = sources[entry["mesh"]]
            references = np.array(entry["holds"]["references"] if "holds" in entry else entry["references"])
            kept = references > 0 if (references > 0).any() else np.ones(len(hexes), dtype=bool)
            try:
                m = meshio.read(os.path.join(matrix_dir, "gmsh_%d.msh" % i), file_format="gmsh")
            except BaseException as ex:
                check(False, "gmsh did not rewrite %s: %s" % (name, ex))
                continue
            got = hexahedra(m)
            ok = check(len(got) == kept.sum() and np.allclose(corners(m.points, got), corners(points, hexes[kept]),
                                                             rtol=1e-15, atol=1e-16),
                       "gmsh reads other hexahedra in %s" % name)
            if (references > 0).any():
                physical = cell_values(m, "gmsh:physical")
                ok = check(physical is not None and sorted(physical.tolist()) == sorted(references[kept].tolist()),
                           "%s: gmsh reads physical tags %s" % (name, physical)) and ok
                counts["groups"] += 1
            counts["gmsh"] += 1
            counts["passed"] += 1 if ok else 0
    matrix_result = ("conversion matrix: %d files (%d meshes), %d pass: %d read by meshio, %d by gmsh (.msh), "
                     "%d with their groups compared" % (len(entries), len(sources), counts["passed"],
                                                        counts["meshio"], counts["gmsh"], counts["groups"]))
    if not gmsh:
        matrix_result += "; %d .msh files not checked: gmsh is not installed" % len(msh_entries)

print("\n%-22s %-16s %-38s %s" % ("file", "meshio reads", "we read", "groups kept"))
for row in rows:
    print("%-22s %-16s %-38s %s" % row)
print("\n" + gmsh_result)
print(matrix_result)
if failures:
    print("\n%d checks failed" % len(failures))
    sys.exit(1)
shutil.rmtree(os.path.join(work, "matrix"), ignore_errors=True)  # 900 files, about 75 MB
print("all checks passed")
