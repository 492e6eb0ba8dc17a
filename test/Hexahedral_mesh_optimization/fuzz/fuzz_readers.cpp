// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// libFuzzer targets for the package's readers, one executable per reader
// (HMO_FUZZ_READER, set by CMakeLists.txt): the bytes are written to a
// file in /dev/shm (the readers take file names, and the reference reader
// picks its format by the extension), then read. Any crash, leak or
// undefined behaviour (the targets are built with ASan and UBSan) is a
// finding; a reader saying no, with its message, is the expected answer.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#define HMO_FUZZ_MEDIT 1
#define HMO_FUZZ_VTK 2
#define HMO_FUZZ_VTU 3
#define HMO_FUZZ_OBJ 4
#define HMO_FUZZ_OFF 5
#define HMO_FUZZ_MSH 6
#define HMO_FUZZ_INP 7

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

const char* extension()
{
  switch(HMO_FUZZ_READER)
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
const std::string& scratch_file()
{
  static const struct Scratch
  {
    std::string name;
    Scratch() : name("/dev/shm/hmo_fuzz_" + std::to_string(::getpid()) + extension()) {}
    ~Scratch() { std::remove(name.c_str()); }
  } scratch;
  return scratch.name;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string& file = scratch_file();
  {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if(!f) return 0;
    if(size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
#if HMO_FUZZ_READER == HMO_FUZZ_OBJ || HMO_FUZZ_READER == HMO_FUZZ_OFF
  CGAL::Surface_mesh<K::Point_3> surface;
  std::string why;
  CGAL::IO::read_reference_surface(file, surface, &why);
#else
  CGAL::Indexed_hex_mesh<K::Point_3> mesh;
  CGAL::IO::Hex_mesh_io_error error;
  std::vector<std::string> warnings;
  CGAL::IO::read_hex_mesh(file, mesh, &error, &warnings);
#endif
  return 0;
}
