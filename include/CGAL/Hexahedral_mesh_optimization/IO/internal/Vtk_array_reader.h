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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_ARRAY_READER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_ARRAY_READER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The numbers of one array of a legacy VTK file (POINTS, CELLS, CELL_TYPES,
// attribute data), read either as whitespace separated text, which may span
// lines in any way, or as a block of big-endian binary values (the legacy
// format's byte order, whatever the machine).

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// a value type of the legacy format ("float", "double", "int", "vtktypeint64"...)
struct Vtk_data_type
{
  std::string name;
  std::size_t bytes = 0;  // 0: unknown type
  bool real = false;
  bool is_signed = true;
  bool bit = false;       // "bit": packed, 8 values per byte

  bool known() const { return bytes != 0 || bit; }
};

inline Vtk_data_type vtk_data_type(std::string_view name)
{
  struct Entry { const char* name; std::size_t bytes; bool real; bool is_signed; };
  static const Entry table[] = {
    {"char", 1, false, true}, {"signed_char", 1, false, true}, {"unsigned_char", 1, false, false},
    {"short", 2, false, true}, {"unsigned_short", 2, false, false},
    {"int", 4, false, true}, {"unsigned_int", 4, false, false},
    {"long", 8, false, true}, {"unsigned_long", 8, false, false},
    {"vtkIdType", 4, false, true},  // the legacy writer stores vtkIdType as int
    {"float", 4, true, true}, {"double", 8, true, true},
    {"vtktypeint8", 1, false, true}, {"vtktypeuint8", 1, false, false},
    {"vtktypeint16", 2, false, true}, {"vtktypeuint16", 2, false, false},
    {"vtktypeint32", 4, false, true}, {"vtktypeuint32", 4, false, false},
    {"vtktypeint64", 8, false, true}, {"vtktypeuint64", 8, false, false},
    {"vtktypefloat32", 4, true, true}, {"vtktypefloat64", 8, true, true}
  };
  Vtk_data_type t;
  t.name = std::string(name);
  if(iequals(name, "bit"))
  {
    t.bit = true;
    return t;
  }
  for(const Entry& e : table)
    if(iequals(name, e.name))
    {
      t.bytes = e.bytes;
      t.real = e.real;
      t.is_signed = e.is_signed;
      break;
    }
  return t;
}

inline Vtk_data_type vtk_int32_type() { return vtk_data_type("int"); }

class Vtk_array_reader
{
public:
  Vtk_array_reader(Text_scanner& sc, const Read_context& ctx, bool binary)
    : sc_(sc), ctx_(ctx), binary_(binary)
  {}

  /// Starts an array of `count` values of `type`, for section `what`
  /// ("POINTS"), announced as `records` `record_word` ("8979 points") on
  /// the line of `header`. In binary the data starts on the next line.
  bool begin(const std::string& what, const Vtk_data_type& type, std::size_t count,
             std::size_t records, const std::string& record_word, const Token& header)
  {
    what_ = what;
    type_ = type;
    count_ = count;
    done_ = 0;
    record_start_ = 0;
    records_ = records;
    record_word_ = record_word;
    records_done_ = 0;
    if(!binary_)
      return true;
    if(!type.known())
      return ctx_.fail(header.line, what + ": unknown data type " + quote_token(type.name) + " (line " +
                                      std::to_string(header.line) + ")");
    if(!sc_.finish_line())
      return ctx_.fail(header.line, what + ": unexpected text after the header (line " +
                                      std::to_string(header.line) + "); binary data must start on the next line");
    if(!type.bit && count > (std::numeric_limits<std::size_t>::max)() / type.bytes)
      return ctx_.fail(header.line, what + ": absurd number of values (line " +
                                      std::to_string(header.line) + ")");
    const std::size_t bytes = type.bit ? (count + 7) / 8 : count * type.bytes;
    block_offset_ = sc_.offset();
    if(sc_.remaining() < bytes)
      return ctx_.fail(0, what + ": expected " + std::to_string(records) + " " + record_word + " (" +
                            std::to_string(bytes) + " bytes of binary data from byte " +
                            std::to_string(block_offset_) + "), file ends " +
                            std::to_string(sc_.remaining()) + " bytes later");
    block_ = sc_.take(bytes);
    return true;
  }

  /// the caller counts whole records for the messages about truncated data
  void set_records_done(std::size_t n)
  {
    records_done_ = n;
    record_start_ = done_;
  }

  bool next_real(double& v)
  {
    if(binary_)
    {
      const char* p = block_ + done_ * type_.bytes;
      last_ = block_offset_ + done_ * type_.bytes;
      ++done_;
      v = type_.real ? decode_real(p) : static_cast<double>(decode_integer(p));
      return true;
    }
    Token t;
    if(!next_token(t))
      return false;
    const Number_status st = parse_real(t.text, v);
    return st == Number_status::ok || bad_token(t, st, "a number");
  }

  bool next_integer(long long& v)
  {
    if(binary_)
    {
      const char* p = block_ + done_ * type_.bytes;
      last_ = block_offset_ + done_ * type_.bytes;
      ++done_;
      if(type_.real)
        return ctx_.fail(0, what_ + ": integer data expected, not " + type_.name);
      v = decode_integer(p);
      return true;
    }
    Token t;
    if(!next_token(t))
      return false;
    const Number_status st = parse_integer(t.text, v);
    return st == Number_status::ok || bad_token(t, st, "an integer");
  }

  /// steps over all the values (attribute data of no use here)
  bool skip_all()
  {
    if(binary_)
      return true;  // the block was taken by begin()
    double v = 0.;
    for(std::size_t i = done_; i < count_; ++i)
    {
      set_records_done(i);
      if(!next_real(v))
        return false;
    }
    return true;
  }

  /// the line (text) or byte offset (binary) of the last value read
  std::size_t last_position() const { return last_; }
  bool binary() const { return binary_; }

private:
  bool next_token(Token& t)
  {
    if(!sc_.next(t))
      return ctx_.fail(sc_.line(), what_ + ": expected " + std::to_string(records_) + " " + record_word_ +
                                     ", file ends after " + std::to_string(records_done_));
    last_ = t.line;
    ++done_;
    return true;
  }

  bool bad_token(const Token& t, Number_status st, const char* expected)
  {
    const std::string at = " (line " + std::to_string(t.line) + ")";
    if(st == Number_status::out_of_range)
      return ctx_.fail(t.line, "number " + quote_token(t.text) + " out of range in " + what_ + at);
    if(starts_with_letter(t.text) && done_ == record_start_ + 1)  // a keyword where a record should start
      return ctx_.fail(t.line, what_ + ": expected " + std::to_string(records_) + " " + record_word_ +
                                 ", found only " + std::to_string(records_done_) + " before " +
                                 quote_token(t.text) + at);
    return ctx_.fail(t.line, "non-numeric token " + quote_token(t.text) + " in " + what_ + at +
                               ": expected " + expected);
  }

  std::uint64_t load_big_endian(const char* p) const
  {
    std::uint64_t u = 0;
    for(std::size_t i = 0; i < type_.bytes; ++i)
      u = (u << 8) | static_cast<unsigned char>(p[i]);
    return u;
  }

  double decode_real(const char* p) const
  {
    const std::uint64_t u = load_big_endian(p);
    if(type_.bytes == 4)
    {
      const std::uint32_t u32 = static_cast<std::uint32_t>(u);
      float f;
      std::memcpy(&f, &u32, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &u, 8);
    return d;
  }

  long long decode_integer(const char* p) const
  {
    const std::uint64_t u = load_big_endian(p);
    const std::size_t bits = 8 * type_.bytes;
    if(type_.is_signed && bits < 64 && (u >> (bits - 1)) != 0)  // sign extension
      return static_cast<long long>(u | (~std::uint64_t(0) << bits));
    return static_cast<long long>(u);
  }

  Text_scanner& sc_;
  const Read_context& ctx_;
  bool binary_;
  std::string what_;
  Vtk_data_type type_;
  std::size_t count_ = 0, done_ = 0;
  std::size_t records_ = 0, records_done_ = 0;
  std::size_t record_start_ = 0;  // index of the first value of the current record
  std::string record_word_;
  const char* block_ = nullptr;
  std::size_t block_offset_ = 0;
  std::size_t last_ = 0;
};

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_ARRAY_READER_H
