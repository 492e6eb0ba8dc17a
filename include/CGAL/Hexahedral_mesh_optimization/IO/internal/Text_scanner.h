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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_TEXT_SCANNER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_TEXT_SCANNER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// A whitespace tokenizer over an in-memory buffer that tracks line numbers,
// with number parsing by std::from_chars (no locale, no stream per token).
// It can also hand out raw byte ranges, for the binary blocks of legacy VTK.

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

struct Token
{
  std::string_view text;
  std::size_t line = 0;  // 1-based line where the token starts
};

inline bool is_blank(char c)
{
  return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

class Text_scanner
{
public:
  /// scans [begin, end); `first_line` is the line number of `begin`;
  /// when `comment` is not '\0', a token starting with it starts a comment
  /// that runs to the end of its line
  Text_scanner(const char* begin, const char* end, std::size_t first_line = 1, char comment = '\0')
    : begin_(begin), cur_(begin), end_(end), line_(first_line), comment_(comment)
  {}

  /// the next token, or false at the end of the buffer
  bool next(Token& t)
  {
    skip_blanks_and_comments();
    if(cur_ == end_)
      return false;
    const char* start = cur_;
    while(cur_ != end_ && !is_blank(*cur_))
      ++cur_;
    t.text = std::string_view(start, static_cast<std::size_t>(cur_ - start));
    t.line = line_;
    return true;
  }

  /// the next token without consuming it
  bool peek(Token& t) const
  {
    Text_scanner copy(*this);
    return copy.next(t);
  }

  bool at_end()
  {
    skip_blanks_and_comments();
    return cur_ == end_;
  }

  /// the line of the current position
  std::size_t line() const { return line_; }
  /// bytes from the beginning of the buffer to the current position
  std::size_t offset() const { return static_cast<std::size_t>(cur_ - begin_); }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - cur_); }

  /// the next token if it is on the current line (for optional header fields)
  bool next_on_line(Token& t)
  {
    const char* p = cur_;
    while(p != end_ && (*p == ' ' || *p == '\t' || *p == '\r'))
      ++p;
    if(p == end_ || *p == '\n')
      return false;
    cur_ = p;
    return next(t);
  }

  /// the rest of the current line without its end of line; moves to the
  /// start of the next line; false at the end of the buffer
  bool next_line(std::string_view& l)
  {
    if(cur_ == end_)
      return false;
    const char* start = cur_;
    while(cur_ != end_ && *cur_ != '\n')
      ++cur_;
    const char* stop = cur_;
    if(stop != start && stop[-1] == '\r')
      --stop;
    l = std::string_view(start, static_cast<std::size_t>(stop - start));
    if(cur_ != end_)
    {
      ++cur_;
      ++line_;
    }
    return true;
  }

  /// skips spaces up to and including the end of the current line (binary
  /// data starts right after it); false if something else comes first
  bool finish_line()
  {
    const char* p = cur_;
    while(p != end_ && (*p == ' ' || *p == '\t' || *p == '\r'))
      ++p;
    if(p == end_)
    {
      cur_ = p;
      return true;
    }
    if(*p != '\n')
      return false;
    cur_ = p + 1;
    ++line_;
    return true;
  }

  /// consumes `n` raw bytes (n <= remaining()) and returns their start; the
  /// line count follows the newline bytes among them, so that later lines
  /// keep the numbers a text editor shows
  const char* take(std::size_t n)
  {
    const char* start = cur_;
    cur_ += n;
    line_ += static_cast<std::size_t>(std::count(start, cur_, '\n'));
    return start;
  }

private:
  void skip_blanks_and_comments()
  {
    for(;;)
    {
      while(cur_ != end_ && is_blank(*cur_))
      {
        if(*cur_ == '\n')
          ++line_;
        ++cur_;
      }
      if(cur_ == end_ || comment_ == '\0' || *cur_ != comment_)
        return;
      while(cur_ != end_ && *cur_ != '\n')
        ++cur_;
    }
  }

  const char* begin_;
  const char* cur_;
  const char* end_;
  std::size_t line_;
  char comment_;
};

// ------------------------------------------------------------------ numbers

enum class Number_status { ok, not_a_number, out_of_range };

/// parses the whole token as a double ("nan" and "inf" are accepted here and
/// rejected later by the validation, which names the vertex)
inline Number_status parse_real(std::string_view s, double& v)
{
  const char* b = s.data();
  const char* e = b + s.size();
  if(b != e && *b == '+')
    ++b;
  const std::from_chars_result r = std::from_chars(b, e, v);
  if(r.ec == std::errc::result_out_of_range && r.ptr == e)
    return Number_status::out_of_range;
  if(r.ec != std::errc() || r.ptr != e || b == e)
    return Number_status::not_a_number;
  return Number_status::ok;
}

/// parses the whole token as a decimal integer
inline Number_status parse_integer(std::string_view s, long long& v)
{
  const char* b = s.data();
  const char* e = b + s.size();
  if(b != e && *b == '+')
    ++b;
  const std::from_chars_result r = std::from_chars(b, e, v);
  if(r.ec == std::errc::result_out_of_range && r.ptr == e)
    return Number_status::out_of_range;
  if(r.ec != std::errc() || r.ptr != e || b == e)
    return Number_status::not_a_number;
  return Number_status::ok;
}

inline Number_status parse_int(std::string_view s, int& v)
{
  long long w = 0;
  const Number_status st = parse_integer(s, w);
  if(st != Number_status::ok)
    return st;
  if(w < INT_MIN || w > INT_MAX)
    return Number_status::out_of_range;
  v = static_cast<int>(w);
  return Number_status::ok;
}

/// a token for an error message: quoted, at most 40 characters, with
/// unprintable bytes (binary garbage) shown as \xNN
inline std::string quote_token(std::string_view s)
{
  static const char hex[] = "0123456789abcdef";
  std::string q = "'";
  const std::size_t shown = (std::min)(s.size(), std::size_t(40));
  for(std::size_t i = 0; i < shown; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if(c >= 32 && c < 127)
      q += static_cast<char>(c);
    else
    {
      q += "\\x";
      q += hex[c >> 4];
      q += hex[c & 15];
    }
  }
  if(shown < s.size())
    q += "...";
  q += "'";
  return q;
}

inline bool starts_with_letter(std::string_view s)
{
  return !s.empty() && ((s[0] >= 'A' && s[0] <= 'Z') || (s[0] >= 'a' && s[0] <= 'z'));
}

inline char to_lower_ascii(char c)
{
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

inline bool iequals(std::string_view a, std::string_view b)
{
  if(a.size() != b.size())
    return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(to_lower_ascii(a[i]) != to_lower_ascii(b[i]))
      return false;
  return true;
}

inline std::string to_lower(std::string_view s)
{
  std::string r(s);
  for(char& c : r)
    c = to_lower_ascii(c);
  return r;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_TEXT_SCANNER_H
