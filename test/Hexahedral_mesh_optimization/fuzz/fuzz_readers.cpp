// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The body of the libFuzzer targets of the package's readers, compiled once
// for all of them (CMakeLists.txt): `hmo_fuzz_read(reader, data, size)`
// writes the bytes to a file in /dev/shm (the readers take file names, and
// the reference reader picks its format by the extension), then reads it
// with that reader. Each target (fuzz_target.cpp, one executable per
// reader) calls it with its own reader. Any crash, leak or undefined
// behaviour (the targets are built with ASan and UBSan) is a finding; a
// reader saying no, with its message, is the expected answer.

#include "fuzz_readers.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

const char* extension(int reader)
{
  switch(reader)
  {
  case HMO_FUZZ_MEDIT: return ".mesh";
  case HMO_FUZZ_VTK: return ".vtk";
  case HMO_FUZZ_VTU: return ".vtu";
  case HMO_FUZZ_OBJ: return ".obj";
  case HMO_FUZZ_MSH: return ".msh";
  case HMO_FUZZ_INP: return ".inp";
  default: return ".off";
  }
}

/// a file of this process in /dev/shm (memory), removed at exit
const std::string& scratch_file(int reader)
{
  static const struct Scratch
  {
    std::string name;
    explicit Scratch(int r) : name("/dev/shm/hmo_fuzz_" + std::to_string(::getpid()) + extension(r)) {}
    ~Scratch() { std::remove(name.c_str()); }
  } scratch(reader);
  return scratch.name;
}

} // namespace

int hmo_fuzz_read(int reader, const std::uint8_t* data, std::size_t size)
{
  const std::string& file = scratch_file(reader);
  {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if(!f) return 0;
    if(size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  if(reader == HMO_FUZZ_OBJ || reader == HMO_FUZZ_OFF)
  {
    CGAL::Surface_mesh<K::Point_3> surface;
    std::string why;
    CGAL::IO::read_reference_surface(file, surface, &why);
  }
  else
  {
    CGAL::Indexed_hex_mesh<K::Point_3> mesh;
    CGAL::IO::Hex_mesh_io_error error;
    std::vector<std::string> warnings;
    CGAL::IO::read_hex_mesh(file, mesh, &error, &warnings);
  }
  return 0;
}
