# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# `pip install .` of the Python package hexmesh_optimization from a source
# checkout, offline, with Debian's python3-pip, python3-setuptools,
# python3-venv and pybind11-dev:
#
#   python3 -m venv --system-site-packages venv    # numpy (and meshio) from Debian
#   venv/bin/pip install --no-build-isolation .
#   venv/bin/python -m hexmesh_optimization IN OUT [options]
#
# It compiles python/hexmesh_optimization_module.cpp with the headers of
# include/ as python/CMakeLists.txt does (the same definitions and flags: CGAL,
# Eigen, GMP/MPFR, and TetGen, Exodus II and TBB when they are installed).
# Nothing is downloaded: the headers and libraries are those of the system.

import os
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
MULTIARCH = sysconfig.get_config_var("MULTIARCH") or ""
INCLUDE_DIRS = ["/usr/local/include", "/usr/include"]
LIBRARY_DIRS = ["/usr/local/lib", os.path.join("/usr/lib", MULTIARCH), "/usr/lib", "/usr/lib64"]


def header_dir(header, candidates=INCLUDE_DIRS):
    """the folder of `candidates` that holds `header`, or None"""
    for d in candidates:
        if os.path.isfile(os.path.join(d, header)):
            return d
    return None


def has_library(*names):
    """the first of `names` (libNAME.so) found in the library folders, or None"""
    for name in names:
        for d in LIBRARY_DIRS:
            if os.path.exists(os.path.join(d, "lib%s.so" % name)):
                return name
    return None


def pybind11_include():
    try:
        import pybind11  # pip's pybind11, or Debian's python3-pybind11
        return pybind11.get_include()
    except ImportError:
        d = header_dir("pybind11/pybind11.h")  # Debian's pybind11-dev
        if d is None:
            raise SystemExit("hexmesh_optimization: the pybind11 headers were not found (Debian: pybind11-dev)")
        return d


def required(header, candidates, package):
    d = header_dir(header, candidates)
    if d is None:
        raise SystemExit("hexmesh_optimization: %s was not found (Debian: %s)" % (header, package))
    return d


include_dirs = [os.path.join(ROOT, "include"), pybind11_include(),
                required("CGAL/version.h", INCLUDE_DIRS, "libcgal-dev"),
                required("Eigen/Core", [os.path.join(d, "eigen3") for d in INCLUDE_DIRS], "libeigen3-dev")]
# as python/CMakeLists.txt (CGAL::CGAL, CGAL::Eigen3_support, the hmo target)
define_macros = [("NDEBUG", None), ("BOOST_ALLOW_DEPRECATED_HEADERS", None), ("BOOST_ALL_NO_LIB", None),
                 ("CGAL_EIGEN3_ENABLED", None), ("CGAL_USE_GMPXX", "1")]
libraries = ["gmpxx", "mpfr", "gmp"]
found = []
if header_dir("tetgen.h") and has_library("tet", "tetgen"):
    define_macros += [("TETLIBRARY", None), ("CGAL_HMO_HAVE_TETGEN", None)]
    libraries.append(has_library("tet", "tetgen"))
    found.append("TetGen")
if header_dir("exodusII.h") and has_library("exoIIv2c", "exodus") and has_library("netcdf"):
    define_macros.append(("CGAL_HMO_HAVE_EXODUS", None))
    libraries += [has_library("exoIIv2c", "exodus"), "netcdf"]
    found.append("Exodus II")
if header_dir("tbb/tbb.h") and has_library("tbb"):
    define_macros.append(("CGAL_LINKED_WITH_TBB", None))
    libraries += ["tbb"] + (["tbbmalloc"] if has_library("tbbmalloc") else [])
    found.append("TBB")
print("hexmesh_optimization: building with %s" % (", ".join(found) or "none of TetGen, Exodus II, TBB"))

# the flags of the CMake Release build (pybind11_add_module NO_EXTRAS)
COMPILE_FLAGS = ["-std=c++17", "-O3", "-fvisibility=hidden", "-frounding-math", "-Wall", "-Wextra"]


class Build_ext(build_ext):
    """without the interpreter's own -g and -O2 (Debian's python3 adds
    them; -g makes a CGAL module several times larger and slower to build)"""

    def build_extensions(self):
        for attribute in ("compiler_so", "compiler_cxx", "linker_so"):
            command = getattr(self.compiler, attribute, None)
            if command:
                setattr(self.compiler, attribute,
                        [f for f in command if f not in ("-g", "-O2", "-Wstrict-prototypes")])
        build_ext.build_extensions(self)


setup(
    ext_modules=[Extension(
        "hexmesh_optimization._hexmesh_optimization",
        sources=["python/hexmesh_optimization_module.cpp"],
        include_dirs=include_dirs,
        define_macros=define_macros,
        libraries=libraries + ["pthread"],
        extra_compile_args=COMPILE_FLAGS,
        language="c++",
    )],
    cmdclass={"build_ext": Build_ext},
    # not build/, CMake's build folder in the README
    options={"build": {"build_base": "build-python"}},
)
