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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_XML_SCANNER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_XML_SCANNER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Just enough XML for VTK's .vtu files: the tags in order, with their
// attributes (entities decoded) and line numbers; the text between tags is
// left in the buffer for the caller, who knows where an element's content
// starts (after its start tag) and ends (at its end tag). Comments,
// declarations, processing instructions and CDATA sections are skipped.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

struct Xml_tag
{
  std::string_view name;
  std::vector<std::pair<std::string_view, std::string> > attributes;
  bool closing = false;       // </name>
  bool self_closing = false;  // <name ... />
  const char* begin = nullptr;  // the '<'
  const char* end = nullptr;    // just after the '>'
  std::size_t line = 0;       // line of the '<'
  std::size_t end_line = 0;   // line of the '>'

  /// the value of attribute `name`, or null
  const std::string* attribute(std::string_view key) const
  {
    for(const auto& a : attributes)
      if(a.first == key)
        return &a.second;
    return nullptr;
  }
};

class Xml_scanner
{
public:
  Xml_scanner(const char* begin, const char* end) : cur_(begin), end_(end) {}

  /// the next tag; false at the end of the buffer or on malformed XML
  /// (then `error()` is not empty)
  bool next(Xml_tag& tag)
  {
    for(;;)
    {
      const char* lt = static_cast<const char*>(std::memchr(cur_, '<', static_cast<std::size_t>(end_ - cur_)));
      if(lt == nullptr)
      {
        advance_to(end_);
        return false;
      }
      advance_to(lt);
      if(starts_with("<!--"))
      {
        if(!skip_past("-->"))
          return false;
        continue;
      }
      if(starts_with("<![CDATA["))
      {
        if(!skip_past("]]>"))
          return false;
        continue;
      }
      if(starts_with("<?"))
      {
        if(!skip_past("?>"))
          return false;
        continue;
      }
      if(starts_with("<!"))
      {
        if(!skip_past(">"))
          return false;
        continue;
      }
      return read_tag(tag);
    }
  }

  const std::string& error() const { return error_; }
  std::size_t error_line() const { return error_line_; }
  std::size_t line() const { return line_; }

private:
  bool starts_with(const char* s) const
  {
    const std::size_t n = std::strlen(s);
    return static_cast<std::size_t>(end_ - cur_) >= n && std::memcmp(cur_, s, n) == 0;
  }

  void advance_to(const char* p)
  {
    line_ += static_cast<std::size_t>(std::count(cur_, p, '\n'));
    cur_ = p;
  }

  bool skip_past(const char* terminator)
  {
    const std::string_view rest(cur_, static_cast<std::size_t>(end_ - cur_));
    const std::size_t at = rest.find(terminator);
    if(at == std::string_view::npos)
      return fail("unterminated markup starting");
    advance_to(cur_ + at + std::strlen(terminator));
    return true;
  }

  bool fail(const std::string& what)
  {
    error_ = "malformed XML: " + what + " at line " + std::to_string(line_);
    error_line_ = line_;
    return false;
  }

  static bool is_name_char(char c)
  {
    return !is_blank(c) && c != '/' && c != '>' && c != '=' && c != '<' && c != '"' && c != '\'';
  }

  void skip_blanks()
  {
    const char* p = cur_;
    while(p != end_ && is_blank(*p))
      ++p;
    advance_to(p);
  }

  bool read_tag(Xml_tag& tag)
  {
    tag = Xml_tag();
    tag.begin = cur_;
    tag.line = line_;
    ++cur_;  // '<'
    if(cur_ != end_ && *cur_ == '/')
    {
      tag.closing = true;
      ++cur_;
    }
    const char* name = cur_;
    while(cur_ != end_ && is_name_char(*cur_))
      ++cur_;
    tag.name = std::string_view(name, static_cast<std::size_t>(cur_ - name));
    if(tag.name.empty())
      return fail("tag without a name");
    for(;;)
    {
      skip_blanks();
      if(cur_ == end_)
        return fail("unterminated tag <" + std::string(tag.name) + "> starting");
      if(*cur_ == '>')
        break;
      if(*cur_ == '/' && cur_ + 1 != end_ && cur_[1] == '>')
      {
        tag.self_closing = true;
        ++cur_;
        break;
      }
      if(tag.closing)
        return fail("unexpected text in </" + std::string(tag.name) + ">");
      const char* key = cur_;
      while(cur_ != end_ && is_name_char(*cur_))
        ++cur_;
      const std::string_view k(key, static_cast<std::size_t>(cur_ - key));
      skip_blanks();
      if(k.empty() || cur_ == end_ || *cur_ != '=')
        return fail("attribute without a value in <" + std::string(tag.name) + ">");
      ++cur_;
      skip_blanks();
      if(cur_ == end_ || (*cur_ != '"' && *cur_ != '\''))
        return fail("unquoted attribute value in <" + std::string(tag.name) + ">");
      const char quote = *cur_++;
      const char* value = cur_;
      const char* close = static_cast<const char*>(std::memchr(cur_, quote, static_cast<std::size_t>(end_ - cur_)));
      if(close == nullptr)
        return fail("unterminated attribute value in <" + std::string(tag.name) + ">");
      advance_to(close);
      ++cur_;
      tag.attributes.emplace_back(k, decode(std::string_view(value, static_cast<std::size_t>(close - value))));
    }
    ++cur_;  // '>'
    tag.end = cur_;
    tag.end_line = line_;
    return true;
  }

  /// replaces the predefined and numeric character references
  static std::string decode(std::string_view s)
  {
    std::string r;
    r.reserve(s.size());
    for(std::size_t i = 0; i < s.size(); ++i)
    {
      if(s[i] != '&')
      {
        r += s[i];
        continue;
      }
      const std::size_t semi = s.find(';', i);
      if(semi == std::string_view::npos)
      {
        r += s[i];
        continue;
      }
      const std::string_view e = s.substr(i + 1, semi - i - 1);
      if(e == "lt") r += '<';
      else if(e == "gt") r += '>';
      else if(e == "amp") r += '&';
      else if(e == "quot") r += '"';
      else if(e == "apos") r += '\'';
      else if(!e.empty() && e[0] == '#')
      {
        const bool hexadecimal = e.size() > 1 && (e[1] == 'x' || e[1] == 'X');
        const std::string digits(e.substr(hexadecimal ? 2 : 1));
        const unsigned long c = std::strtoul(digits.c_str(), nullptr, hexadecimal ? 16 : 10);
        if(c < 128)
          r += static_cast<char>(c);
        else
          r += '?';  // names in .vtu files are ASCII in practice
      }
      else
      {
        r += s.substr(i, semi - i + 1);
      }
      i = semi;
    }
    return r;
  }

  const char* cur_;
  const char* end_;
  std::size_t line_ = 1;
  std::string error_;
  std::size_t error_line_ = 0;
};

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_XML_SCANNER_H
