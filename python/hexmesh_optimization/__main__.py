# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""python -m hexmesh_optimization INPUT OUTPUT [options]

The pipeline of the command-line tool hexmesh-optimize, from Python: reads
the mesh with its groups, checks the output (and --report) before any work,
optimises (or only untangles), and writes the mesh with its groups and the
per-hexahedron scaled Jacobian where the format has cell fields. A progress
bar is drawn on standard error when it is a terminal. Exit status as
hexmesh-optimize's: 0, 4 when inverted (or uncertified) elements remain, 5
when the time limit cut the run short, 2 for a bad argument, 1 on an error
(a message naming the file and the problem; no output written), 130 on
Ctrl-C (nothing written).
"""

import argparse
import json
import os
import sys

from . import _hexmesh_optimization as _hmo
from . import optimize, quality, scaled_jacobian, untangle

# the options of hexmesh-optimize that take a value: (flag, keyword of the
# Python functions, type, help)
_VALUE_OPTIONS = [
    ("--target-msj", "target_msj", float, "stop raising the minimum scaled Jacobian at X (default 1)"),
    ("--sharp-angle", "sharp_angle", float, "dihedral angle below which a boundary edge is a feature (default 165)"),
    ("--reference-feature-angle", "reference_feature_angle", float,
     "with --reference: its edges below this angle are creases the boundary recovers (default 150; 0: off)"),
    ("--crease-seed-angle", "crease_seed_angle", float,
     "quality stages: a crease starts only at an edge below DEG (default 180: off)"),
    ("--turn-focus-band", "turn_focus_band", float,
     "quality stages: the turns' ASJ pass reshapes the elements below MSJ + X (default 0.15)"),
    ("--surface-tolerance", "surface_tolerance", float,
     "largest surface error the quality stages may cause, relative to the bounding-box diagonal (default 0.005)"),
    ("--time-limit", "time_limit", float, "hard stop after SECONDS of optimisation (default: none)"),
    ("--threads", "threads", int, "number of threads (default: every core); the output is the same for any N"),
]
# the switches: (flag, keyword, value it sets, help)
_SWITCHES = [
    ("--frozen-surface", "relax_surface", False, "never relax the surface while untangling"),
    ("--no-pull-back", "pull_back", False, "skip the inversion-free pull-back of a relaxed surface"),
    ("--no-asj", "asj_smoothing", False, "skip the final smoothing of the average scaled Jacobian"),
    ("--no-coarse-level", "coarse_level_start", False,
     "do not optimise a mesh recognised as a 1->8 refinement at its coarse level first"),
]
_UNTANGLE_KEYWORDS = {"sharp_angle", "reference_feature_angle", "surface_tolerance", "time_limit", "threads",
                      "relax_surface", "method"}


def _parser():
    p = argparse.ArgumentParser(
        prog="python -m hexmesh_optimization",
        description="Untangles a hexahedral mesh and raises its minimum scaled Jacobian, as hexmesh-optimize does: "
                    "reads INPUT (.mesh, .vtk, .vtu, .msh, .inp, .exo/.e) and writes OUTPUT with the same groups "
                    "where its format holds them (a warning, before the work, for those it does not).")
    p.add_argument("input", metavar="INPUT")
    p.add_argument("output", metavar="OUTPUT")
    p.add_argument("--untangle", action="store_true", help="only untangle (default: the whole pipeline)")
    p.add_argument("--method", choices=["package", "paper"], help="'package' (default) or 'paper' (Xu & Chen 2018)")
    p.add_argument("--reference", metavar="SURFACE",
                   help="triangle surface (.obj .off .ply .stl) the boundary must stay on (default: the input's)")
    for flag, _, kind, text in _VALUE_OPTIONS:
        p.add_argument(flag, type=kind, metavar="N" if kind is int else "X", help=text)
    for flag, _, _, text in _SWITCHES:
        p.add_argument(flag, action="store_true", help=text)
    p.add_argument("--output-format", metavar="FORMAT",
                   help="write OUTPUT in FORMAT whatever its extension: mesh, vtk, vtk-binary, vtu, msh, msh41, "
                        "msh41-binary, msh22, msh22-binary, inp, exo")
    p.add_argument("--report", metavar="FILE.json",
                   help="write the quality before and after and the optimisation's report as JSON")
    p.add_argument("--quiet", action="store_true", help="print only warnings and errors")
    return p


class _ProgressBar:
    """one line per stage on a terminal: the share of the elements to fix that are fixed"""

    def __init__(self, stream):
        self.stream = stream
        self.stage = None
        self.start = 0

    def __call__(self, stage, value):
        if isinstance(value, float):  # 1.0: the stage is done
            self._draw(stage, 1.0, "done")
            self.stream.write("\n")
            self.stream.flush()
            self.stage = None
            return
        if stage != self.stage:
            self.stage, self.start = stage, max(value, 1)
        self._draw(stage, 1.0 - min(value, self.start) / self.start, "%d left" % value)

    def _draw(self, stage, fraction, text):
        width = 30
        filled = int(round(fraction * width))
        self.stream.write("\r%-28s [%s%s] %3d%% %-12s" % (stage[:28], "#" * filled, "." * (width - filled),
                                                          int(round(100 * fraction)), text))
        self.stream.flush()


def _summary(q):
    return "%d hexahedra, %d inverted, MSJ %.4f, ASJ %.4f" % (q["hexes"], q["inverted"], q["msj"], q["asj"])


def _quality_json(q):
    return {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in q.items()}


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    err = sys.stderr
    options = {}
    for _, key, _, _ in _VALUE_OPTIONS:
        value = getattr(args, key)
        if value is not None:
            options[key] = value
    for flag, key, value, _ in _SWITCHES:
        if getattr(args, flag[2:].replace("-", "_")):
            options[key] = value
    if args.method:
        options["method"] = args.method
    function = optimize
    if args.untangle:
        function = untangle
        ignored = sorted(k for k in options if k not in _UNTANGLE_KEYWORDS)
        if ignored:  # a bad command line: exit status 2, before anything is read
            parser.error("--untangle does not take the options of the quality stages (%s)" % ", ".join(ignored))

    def fail(message):
        err.write("error: %s\n" % message)
        return 1

    try:
        mesh = _hmo._MeshFile.read(args.input)
    except (OSError, ValueError) as e:
        return fail(e)
    for w in mesh.warnings:
        err.write("warning: %s: %s\n" % (args.input, w))
    # everything about the outputs before the work
    try:
        for w in mesh.check_output(args.output, args.output_format):
            err.write("warning: %s: %s\n" % (args.output, w))
        if args.report:
            if not args.report.lower().endswith(".json"):
                return fail("%s: --report expects a .json file" % args.report)
            _hmo._check_output_file(args.report)
    except (OSError, ValueError) as e:
        return fail(e)

    points, hexes = mesh.points, mesh.hexes
    before = quality(points, hexes)
    if not args.quiet:
        print("%s: %s" % (args.input, _summary(before)))
    progress = _ProgressBar(err) if err.isatty() and not args.quiet else None
    try:
        new_points, report = function(points, hexes, reference=args.reference, progress=progress, **options)
    except KeyboardInterrupt:
        err.write("\n")
        fail("interrupted: nothing written")
        return 130
    except (OSError, ValueError, TypeError) as e:
        return fail(e)
    after = quality(new_points, hexes)
    for w in report["warnings"]:
        err.write("warning: %s\n" % w)
    try:
        mesh.write(args.output, new_points, {"scaled_jacobian": scaled_jacobian(new_points, hexes)},
                   args.output_format)
        if args.report:  # written next to it, then renamed: never half a file
            temporary = "%s.%d.tmp" % (args.report, os.getpid())
            try:
                with open(temporary, "w") as f:
                    json.dump({"input": args.input, "output": args.output, "before": _quality_json(before),
                               "after": _quality_json(after), "optimization": report}, f, indent=1, default=str)
                os.replace(temporary, args.report)
            finally:
                if os.path.exists(temporary):
                    os.remove(temporary)
    except (OSError, ValueError) as e:
        return fail(e)
    if not args.quiet:
        print("%s: %s (%.1f s)" % (args.output, _summary(after), report["seconds"]))
    if after["inverted"] > 0 or len(after["not_certified"]) > 0:
        return 4
    return 5 if report["time_limit_reached"] else 0


if __name__ == "__main__":
    sys.exit(main())
