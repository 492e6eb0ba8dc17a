// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// All rights reserved.
//
// This file is part of CGAL (www.cgal.org)
//
// $URL$
// $Id$
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : Hexahedral_mesh_optimization contributors

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_LOAD_FILE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_LOAD_FILE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reads a whole file into memory: the readers then parse a buffer, which is
// much faster than extracting tokens from a stream one by one.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// Loads the bytes of `fname` into `content`. On failure returns false and
/// sets `error` to "cannot open: <system reason>" or "cannot read: ...".
inline bool load_file(const std::string& fname, std::string& content, std::string& error)
{
  content.clear();
  errno = 0;
  std::FILE* f = std::fopen(fname.c_str(), "rb");
  if(f == nullptr)
  {
    error = std::string("cannot open: ") + (errno != 0 ? std::strerror(errno) : "unknown error");
    return false;
  }
  // the size is only a hint (the file may be a pipe)
  if(std::fseek(f, 0, SEEK_END) == 0)
  {
    const long size = std::ftell(f);
    if(size > 0)
      content.reserve(static_cast<std::size_t>(size));
    std::rewind(f);
  }
  char chunk[1 << 16];
  for(;;)
  {
    const std::size_t n = std::fread(chunk, 1, sizeof(chunk), f);
    content.append(chunk, n);
    if(n < sizeof(chunk))
      break;
  }
  const bool failed = std::ferror(f) != 0;
  const int reason = errno;
  std::fclose(f);
  if(failed)
  {
    error = std::string("cannot read: ") + (reason != 0 ? std::strerror(reason) : "read error");
    content.clear();
    return false;
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_LOAD_FILE_H
