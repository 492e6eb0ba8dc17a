#!/usr/bin/python3
# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# `pip install .` as a user does it, offline, from a copy of the source
# checkout (include/, python/, setup.py, pyproject.toml, README.md): a fresh
# virtual environment with the system's packages (numpy), pip install
# --no-build-isolation --no-index (the module compiled from source once more),
# then the installed package is imported from the environment and
# `python -m hexmesh_optimization` optimises the bundled bunny_dualsheet.vtk
# (45 inverted hexahedra) on a terminal (a pseudo-terminal: the progress bar
# is drawn) into a .vtu with a JSON report, which are checked; an output in
# a folder that does not exist is refused before the work, and without a
# terminal no progress bar is drawn. Prints the time of each step.
# usage: test_pip_install.py SOURCE_DIR WORK_DIR EXAMPLE_DATA_DIR
# Exit 77 (skipped) when python3-venv or python3-pip is missing.

import json
import os
import shutil
import subprocess
import sys
import time

source, work, data = sys.argv[1:4]

try:
    import ensurepip  # noqa: F401  (Debian: python3-venv)
    import venv  # noqa: F401
except ImportError as e:
    print("skipped: python3-venv is missing:", e)
    sys.exit(77)
try:
    import pip  # noqa: F401  (Debian: python3-pip; the environment sees it with --system-site-packages)
except ImportError as e:
    print("skipped: python3-pip is missing:", e)
    sys.exit(77)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)
    return condition


def step(name, command, **kwargs):
    start = time.monotonic()
    r = subprocess.run(command, capture_output=True, text=True, **kwargs)
    print("%-34s %6.1f s  (exit %d)" % (name, time.monotonic() - start, r.returncode))
    return r


shutil.rmtree(work, ignore_errors=True)
src = os.path.join(work, "src")
os.makedirs(src)
for d in ("include", "python"):
    shutil.copytree(os.path.join(source, d), os.path.join(src, d),
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
for f in ("setup.py", "pyproject.toml", "README.md"):
    shutil.copy(os.path.join(source, f), src)

# the environment of a user: no PYTHONPATH to the build tree
env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
total = time.monotonic()
venv_dir = os.path.join(work, "venv")
r = step("python3 -m venv --system-site-packages", [sys.executable, "-m", "venv", "--system-site-packages", venv_dir],
         env=env)
if not check(r.returncode == 0, "venv: %s" % r.stderr):
    sys.exit(1)
python = os.path.join(venv_dir, "bin", "python")
r = step("pip install --no-build-isolation .", [python, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                                               "--disable-pip-version-check", "."], cwd=src, env=env)
if not check(r.returncode == 0, "pip install: %s\n%s" % (r.stdout[-3000:], r.stderr[-3000:])):
    sys.exit(1)
check(not os.path.exists(os.path.join(src, "build")), "the pip build wrote into build/ (CMake's folder)")

# the package is the one installed in the environment, compiled
r = step("import", [python, "-c", "import hexmesh_optimization as h, os; "
                    "print(os.path.dirname(h.__file__)); print(h._hexmesh_optimization.__file__)"],
         cwd=work, env=env)
if check(r.returncode == 0, "import: %s" % r.stderr):
    package, module = r.stdout.split()
    check(os.path.realpath(package).startswith(os.path.realpath(venv_dir)),
          "imported from %s, not from the environment" % package)
    check(module.endswith(".so"), "the compiled module is %s" % module)

# python -m hexmesh_optimization on a terminal: the progress bar
bunny = os.path.join(data, "bunny_dualsheet.vtk")
out, report = os.path.join(work, "bunny.vtu"), os.path.join(work, "bunny.json")
command = [python, "-m", "hexmesh_optimization", bunny, out, "--report", report]
start = time.monotonic()
master, slave = os.openpty()
p = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=slave, cwd=work, env=env)
os.close(slave)
terminal = b""
while True:
    try:
        chunk = os.read(master, 65536)
    except OSError:  # EIO: the other end is closed
        break
    if not chunk:
        break
    terminal += chunk
stdout = p.stdout.read().decode()
p.wait()
os.close(master)
terminal = terminal.decode(errors="replace")
print("%-34s %6.1f s  (exit %d)" % ("python -m hexmesh_optimization", time.monotonic() - start, p.returncode))
print(stdout.strip())
check(p.returncode == 0, "python -m hexmesh_optimization: exit %d\n%s\n%s" % (p.returncode, stdout, terminal))
check("\r" in terminal and "100% done" in terminal, "no progress bar on the terminal: %r" % terminal[-500:])
check("45 inverted" in stdout and "0 inverted" in stdout, "the summary: %s" % stdout)
r = subprocess.run([python, "-c", "import hexmesh_optimization as h, json, sys; p, x = h.read(sys.argv[1]); "
                    "q = h.quality(p, x); print(json.dumps([len(p), len(x), q['inverted'], q['msj']]))", out],
                   capture_output=True, text=True, cwd=work, env=env)
if check(r.returncode == 0, "cannot read the output: %s" % r.stderr):
    points, hexes, inverted, msj = json.loads(r.stdout)
    check(points == 3724 and hexes == 2832 and inverted == 0 and msj > 0, "the output: %s" % r.stdout)
    with open(report) as f:
        rep = json.load(f)
    certified = rep["optimization"]["certificate"]["certified_valid"]
    check(rep["before"]["inverted"] == 45 and rep["after"]["inverted"] == 0 and certified == 2832,
          "the report: inverted before %s, after %s, certified valid %s" % (
              rep["before"]["inverted"], rep["after"]["inverted"], certified))

# errors before the work: an output folder that does not exist
missing = os.path.join(work, "no_such_folder", "out.vtu")
r = step("output in a missing folder", [python, "-m", "hexmesh_optimization", bunny, missing], cwd=work, env=env)
check(r.returncode == 1 and missing in r.stderr and "does not exist" in r.stderr and r.stdout == "",
      "a missing output folder: exit %d, %r, %r" % (r.returncode, r.stdout, r.stderr))
# without a terminal: no progress bar; the groups a format cannot hold are warned about before the work
out2 = os.path.join(work, "bunny_again.msh")
r = step("--untangle, no terminal", [python, "-m", "hexmesh_optimization", out, out2, "--untangle", "--quiet"],
         cwd=work, env=env)
check(r.returncode == 0 and "\r" not in r.stderr and r.stdout == "" and os.path.exists(out2),
      "--untangle --quiet: exit %d, %r, %r" % (r.returncode, r.stdout, r.stderr))

print("%-34s %6.1f s" % ("total", time.monotonic() - total))
if failures:
    print("%d checks failed" % len(failures))
    sys.exit(1)
shutil.rmtree(src, ignore_errors=True)
print("all checks passed")
