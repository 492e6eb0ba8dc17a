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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_OFF_SOUP_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_OFF_SOUP_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// An ASCII OFF file as a polygon soup, for the reference surfaces. CGAL 5.5's
// OFF scanner converts a negative face index, read as a double, to an
// unsigned integer, which is undefined behaviour (found by fuzzing); this
// reader checks every token and names the line of the first bad one.
//
// Accepted: the keyword OFF with the prefixes ST, C, N (texture coordinates,
// colours and normals after each vertex's 3 coordinates are ignored, as are
// colours after each face's indices), the counts on the keyword's line or
// the next, '#' comments and blank lines. Refused with a message: binary
// OFF, 4OFF and nOFF (other dimensions), counts larger than the file could
// hold, coordinates that are not finite numbers, indices that are not
// non-negative integers, and a file that ends early.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

class Off_lines
{
public:
  explicit Off_lines(const std::string& text) : m_text(text) {}

  /// the next line with something else than a comment, split into tokens;
  /// false at the end of the file
  bool next(std::vector<std::string>& tokens)
  {
    tokens.clear();
    while(tokens.empty() && m_at < m_text.size())
    {
      ++m_line;
      std::size_t end = m_text.find('\n', m_at);
      if(end == std::string::npos) end = m_text.size();
      // a comment starts at the line's first '#', searched within the line
      // only (searched to the end of the text, a file without comments
      // took time quadratic in its number of lines)
      const std::size_t stop = static_cast<std::size_t>(
        std::find(m_text.begin() + m_at, m_text.begin() + end, '#') - m_text.begin());
      std::size_t i = m_at;
      while(i < stop)
      {
        while(i < stop && is_space(m_text[i])) ++i;
        const std::size_t first = i;
        while(i < stop && !is_space(m_text[i])) ++i;
        if(i > first) tokens.push_back(m_text.substr(first, i - first));
      }
      m_at = end + 1;
    }
    return !tokens.empty();
  }

  std::size_t line() const { return m_line; }

private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  const std::string& m_text;
  std::size_t m_at = 0, m_line = 0;
};

/// a non-negative integer written with digits only, at most `max`
inline bool parse_count(const std::string& t, std::size_t max, std::size_t& value)
{
  if(t.empty() || t.size() > 19) return false;
  unsigned long long v = 0;
  for(char c : t)
  {
    if(c < '0' || c > '9') return false;
    v = 10 * v + static_cast<unsigned long long>(c - '0');
  }
  if(v > max) return false;
  value = static_cast<std::size_t>(v);
  return true;
}

/// a finite number (the whole token)
inline bool parse_coordinate(const std::string& t, double& value)
{
  char* end = nullptr;
  errno = 0;
  value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && errno != ERANGE && std::isfinite(value);
}

template <class Point>
bool read_OFF_soup(const std::string& fname, std::vector<Point>& points,
                   std::vector<std::vector<std::size_t> >& polygons, std::string& why)
{
  points.clear();
  polygons.clear();
  std::string text;
  if(!load_file(fname, text, why)) return false;
  Off_lines lines(text);
  std::vector<std::string> t;
  auto fail = [&](const std::string& message) {
    why = fname + ":" + std::to_string(lines.line()) + ": " + message;
    points.clear();
    polygons.clear();
    return false;
  };
  if(!lines.next(t)) return fail("empty file");
  const std::string keyword = t[0];
  const std::size_t off = keyword.rfind("OFF");
  if(off == std::string::npos || off + 3 != keyword.size() ||
     keyword.substr(0, off).find_first_not_of("STCN") != std::string::npos)
    return fail("not an OFF file (its first keyword is '" + keyword.substr(0, 40) + "')");
  // the counts follow the keyword, on its line or the next
  std::vector<std::string> counts(t.begin() + 1, t.end());
  if(!counts.empty() && counts[0] == "BINARY") return fail("binary OFF is not supported: convert it to ASCII");
  if(counts.empty())
  {
    if(!lines.next(t)) return fail("the file ends before the counts");
    counts = t;
  }
  if(counts.size() < 2) return fail("expected the numbers of vertices and faces");
  // each vertex takes at least 6 bytes ("0 0 0\n"), each face at least 8
  std::size_t nv = 0, nf = 0;
  if(!parse_count(counts[0], text.size() / 6, nv))
    return fail("number of vertices '" + counts[0].substr(0, 40) + "' is not a count the file can hold");
  if(!parse_count(counts[1], text.size() / 8, nf))
    return fail("number of faces '" + counts[1].substr(0, 40) + "' is not a count the file can hold");
  points.reserve(nv);
  for(std::size_t v = 0; v < nv; ++v)
  {
    if(!lines.next(t)) return fail("the file ends at vertex " + std::to_string(v) + " of " + std::to_string(nv));
    double c[3];
    if(t.size() < 3) return fail("vertex " + std::to_string(v) + " has fewer than 3 coordinates");
    for(int k = 0; k < 3; ++k)
      if(!parse_coordinate(t[k], c[k]))
        return fail("vertex " + std::to_string(v) + ": '" + t[k].substr(0, 40) + "' is not a finite number");
    points.push_back(Point(c[0], c[1], c[2]));
  }
  polygons.reserve(nf);
  for(std::size_t f = 0; f < nf; ++f)
  {
    if(!lines.next(t)) return fail("the file ends at face " + std::to_string(f) + " of " + std::to_string(nf));
    std::size_t k = 0;
    if(!parse_count(t[0], text.size(), k) || t.size() < k + 1)
      return fail("face " + std::to_string(f) + ": '" + t[0].substr(0, 40) + "' is not its number of vertices");
    std::vector<std::size_t> polygon(k);
    for(std::size_t i = 0; i < k; ++i)
      if(!parse_count(t[i + 1], nv == 0 ? 0 : nv - 1, polygon[i]))
        return fail("face " + std::to_string(f) + ": '" + t[i + 1].substr(0, 40) +
                    "' is not a vertex index (0 to " + std::to_string(nv) + " - 1)");
    polygons.push_back(std::move(polygon));
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_OFF_SOUP_H
