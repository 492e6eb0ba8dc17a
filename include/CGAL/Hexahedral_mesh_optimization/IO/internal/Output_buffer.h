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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_OUTPUT_BUFFER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_OUTPUT_BUFFER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Formatting for the writers: text numbers through std::to_chars (the
// shortest decimal form that reads back to the same double, so round trips
// are exact) and big-endian binary values (legacy VTK), collected in memory
// and handed to an Atomic_output_file in large blocks.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Atomic_output_file.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

class Output_buffer
{
public:
  explicit Output_buffer(Atomic_output_file& file) : file_(file) { buffer_.reserve(capacity + 64); }

  Output_buffer& operator<<(std::string_view s)
  {
    buffer_.append(s.data(), s.size());
    return spill();
  }

  Output_buffer& operator<<(char c)
  {
    buffer_.push_back(c);
    return spill();
  }

  /// shortest decimal text that reads back to exactly `v`
  Output_buffer& operator<<(double v)
  {
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof(text), v);
    buffer_.append(text, static_cast<std::size_t>(r.ptr - text));
    return spill();
  }

  Output_buffer& operator<<(long long v) { return integer(v); }
  Output_buffer& operator<<(int v) { return integer(v); }
  Output_buffer& operator<<(std::size_t v) { return integer(v); }

  void big_endian_int32(std::int32_t v)
  {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    put_big_endian(u, 4);
  }

  void big_endian_double(double v)
  {
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    put_big_endian(u, 8);
  }

  /// the bytes of `v` in the byte order of this machine (binary gmsh files,
  /// whose endianness marker tells the reader)
  template <class T>
  void native(const T& v)
  {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    buffer_.append(bytes, sizeof(T));
    spill();
  }

  /// hands the rest to the file; false if any write failed
  bool flush()
  {
    const bool ok = file_.write(buffer_.data(), buffer_.size());
    buffer_.clear();
    return ok;
  }

private:
  static const std::size_t capacity = 1 << 20;

  template <class Int>
  Output_buffer& integer(Int v)
  {
    char text[24];
    const std::to_chars_result r = std::to_chars(text, text + sizeof(text), v);
    buffer_.append(text, static_cast<std::size_t>(r.ptr - text));
    return spill();
  }

  void put_big_endian(std::uint64_t u, int bytes)
  {
    for(int i = bytes - 1; i >= 0; --i)
      buffer_.push_back(static_cast<char>((u >> (8 * i)) & 0xff));
    spill();
  }

  Output_buffer& spill()
  {
    if(buffer_.size() >= capacity)
      flush();
    return *this;
  }

  Atomic_output_file& file_;
  std::string buffer_;
};

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_OUTPUT_BUFFER_H
