// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The quality report of hexmesh-optimize: printed text (with a histogram
// drawn with bars), a JSON object and an SVG histogram. A report is made of
// one `Mesh_report` per state of the mesh ("input", and "output" once there
// is one); a stage that wants to report more adds fields to `Mesh_report`
// and to the three writers below.

#ifndef HMO_TOOLS_QUALITY_REPORT_H
#define HMO_TOOLS_QUALITY_REPORT_H

#include <CGAL/hex_mesh_quality.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Atomic_output_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace hexmesh_optimize {

/// One of the worst elements of a mesh (--worst).
struct Worst_element
{
  std::size_t id = 0;            ///< 0-based index of the hexahedron (the cell id of ParaView)
  double scaled_jacobian = 0.;   ///< its Verdict scaled Jacobian
  std::array<double, 3> centre = {{0., 0., 0.}}; ///< the mean of its 8 vertices
};

/// The `n` elements of `mesh` with the lowest scaled Jacobian (`sj`, one
/// value per hexahedron, as from `CGAL::hex_mesh_scaled_jacobians()`),
/// worst first, ties by id.
template <class HexMesh>
std::vector<Worst_element> worst_elements(const HexMesh& mesh, const std::vector<double>& sj, std::size_t n)
{
  std::vector<std::size_t> ids(sj.size());
  for(std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  n = (std::min)(n, ids.size());
  auto worse = [&sj](std::size_t a, std::size_t b) { return sj[a] < sj[b] || (sj[a] == sj[b] && a < b); };
  std::partial_sort(ids.begin(), ids.begin() + std::ptrdiff_t(n), ids.end(), worse);
  std::vector<Worst_element> r(n);
  for(std::size_t k = 0; k < n; ++k)
  {
    r[k].id = ids[k];
    r[k].scaled_jacobian = sj[ids[k]];
    for(std::size_t v : mesh.hexahedra[ids[k]])
    {
      r[k].centre[0] += CGAL::to_double(mesh.points[v].x()) / 8.;
      r[k].centre[1] += CGAL::to_double(mesh.points[v].y()) / 8.;
      r[k].centre[2] += CGAL::to_double(mesh.points[v].z()) / 8.;
    }
  }
  return r;
}

/// The figures of one state of the mesh.
struct Mesh_report
{
  std::string file;
  CGAL::Hex_mesh_quality quality;
  /// wall time of what produced this state (input: read + quality;
  /// output: the optimisation stages), negative when not measured
  double seconds = -1.;
  /// Hausdorff distance between this boundary and the input's, relative to
  /// the diagonal of the input's bounding box; negative when not measured
  /// (JSON null)
  double surface_error = -1.;
  /// output: whether the --time-limit hard stop fired during the optimisation
  bool time_limit_reached = false;
  /// output: whether SIGINT or SIGTERM stopped the optimisation
  bool interrupted = false;
  /// output: the optimisation's warnings (`Optimization_result::warnings`)
  std::vector<std::string> warnings;
  /// output: the elements still inverted, and why (`Optimization_result::unresolved`)
  std::vector<CGAL::Hexahedral_mesh_optimization::Unresolved_element> unresolved;
  /// output: the boundary vertices off the reference surface (`Optimization_result::off_surface`)
  std::vector<CGAL::Hexahedral_mesh_optimization::Off_surface_vertex> off_surface;
  /// the exact validity certificate (`CGAL::hex_mesh_validity_certificate()`)
  CGAL::Hexahedral_mesh_optimization::Validity_certificate certificate;
  /// --worst N: its N worst elements, worst first (empty: not asked for)
  std::vector<Worst_element> worst;
};

inline std::string format_fixed(double v, int decimals)
{
  if(!std::isfinite(v))
    return "nan";
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  std::string r = s.str();
  if(r.find_first_not_of("-0.") == std::string::npos && r[0] == '-') // "-0.000"
    r.erase(0, 1);
  return r;
}

/// "[-1.00, -0.90)", "[0.90, 1.00]"; with `aligned`, "[ 0.90,  1.00]"
inline std::string bin_label(int k, bool aligned = false)
{
  typedef CGAL::Hex_mesh_quality Q;
  const bool last = k + 1 == Q::histogram_bins;
  auto number = [aligned](double v) {
    std::string t = format_fixed(v, 2);
    return (aligned && t[0] != '-') ? " " + t : t;
  };
  return "[" + number(Q::bin_lower(k)) + ", " + number(Q::bin_upper(k)) + (last ? "]" : ")");
}

/// The text report of one state, e.g.
///   before: bunny_in.mesh
///     hexes      37734
///     ...
///     [-1.00, -0.90)       0 |
///     [ 0.90,  1.00]   31234 |########################################
inline void print_quality_report(std::ostream& out, const std::string& title, const Mesh_report& r)
{
  typedef CGAL::Hex_mesh_quality Q;
  const Q& q = r.quality;
  out << title << ": " << r.file << "\n"
      << "  hexes       " << q.hexes << "\n"
      << "  vertices    " << q.vertices << "\n"
      << "  inverted    " << q.inverted << "\n"
      << "  MSJ         " << format_fixed(q.msj, 4) << "\n"
      << "  ASJ         " << format_fixed(q.asj, 4) << "\n"
      << "  certified   " << r.certificate.certified_valid() << " of " << r.certificate.hexes
      << " valid (Jacobian > 0 at the 8 corners and the centre, exact signs)";
  if(!r.certificate.all_valid())
  {
    const std::size_t shown = (std::min)(r.certificate.not_certified.size(), std::size_t(10));
    out << "; not certified:";
    for(std::size_t i = 0; i < shown; ++i) out << ' ' << r.certificate.not_certified[i];
    if(shown < r.certificate.not_certified.size())
      out << " and " << r.certificate.not_certified.size() - shown << " more";
  }
  out << "\n";
  if(r.surface_error >= 0.)
    out << "  surface error " << format_fixed(r.surface_error, 5)
        << " (Hausdorff distance to the reference surface, by default the input boundary, / its bounding-box diagonal)\n";
  out << "  scaled Jacobian histogram (bars scale with the count; '#' at least for any count):\n";
  std::size_t max_count = 0;
  for(std::size_t c : q.histogram)
    max_count = (std::max)(max_count, c);
  const int width = 40;
  for(int k = 0; k < Q::histogram_bins; ++k)
  {
    const std::size_t c = q.histogram[k];
    int bar = max_count == 0 ? 0 : int(std::lround(double(width) * double(c) / double(max_count)));
    if(c > 0 && bar == 0)
      bar = 1;
    out << "    " << bin_label(k, true) << std::setw(8) << c << " |" << std::string(bar, '#') << "\n";
    if(k + 1 == Q::histogram_bins / 2)
      out << "    ------------------------- 0 -- inverted (SJ < 0) above this line\n";
  }
  if(!r.worst.empty())
  {
    out << "  " << r.worst.size() << " worst elements (id: 0-based, the cell id of ParaView; centre: mean of the 8 vertices):\n"
        << "    " << std::setw(10) << "id" << std::setw(17) << "scaled Jacobian" << "  centre\n";
    for(const Worst_element& w : r.worst)
    {
      std::ostringstream c;
      c << std::setprecision(6) << "(" << w.centre[0] << ", " << w.centre[1] << ", " << w.centre[2] << ")";
      out << "    " << std::setw(10) << w.id << std::setw(17) << format_fixed(w.scaled_jacobian, 6) << "  " << c.str()
          << "\n";
    }
  }
  out << std::flush;
}

// ------------------------------------------------------------------ files
/// Writes `content` to `path` as the mesh writers write their files
/// (Atomic_output_file): a temporary, unnamed on Linux, renamed over `path`
/// when complete, so that a failed or killed run leaves neither a partial
/// file nor a temporary behind.
inline bool write_text_file(const std::string& path, const std::string& content, std::string& error)
{
  CGAL::Hexahedral_mesh_optimization::internal::io::Atomic_output_file file;
  std::string why;
  if(file.open(path, why))
  {
    file.write(content.data(), content.size());  // a failure is reported by commit()
    if(file.commit(why))
      return true;
  }
  error = path + ": " + why;
  return false;
}

/// Whether `path` can be written, checked before the work whose results it
/// will hold (see probe_output_file).
inline bool check_text_file_writable(const std::string& path, std::string& error)
{
  std::string why;
  if(CGAL::Hexahedral_mesh_optimization::internal::io::probe_output_file(path, why))
    return true;
  error = path + ": " + why;
  return false;
}

inline std::string json_string(const std::string& s)
{
  std::string r = "\"";
  for(unsigned char c : s)
  {
    switch(c)
    {
      case '"': r += "\\\""; break;
      case '\\': r += "\\\\"; break;
      case '\n': r += "\\n"; break;
      case '\r': r += "\\r"; break;
      case '\t': r += "\\t"; break;
      default:
        if(c < 0x20)
        {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          r += buf;
        }
        else
          r += char(c);
    }
  }
  return r + "\"";
}

inline std::string json_number(double v)
{
  if(!std::isfinite(v))
    return "null";
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

inline std::string json_mesh_report(const Mesh_report& r, bool with_output_fields, const std::string& indent)
{
  typedef CGAL::Hex_mesh_quality Q;
  const Q& q = r.quality;
  const std::string in = indent + "  ";
  std::ostringstream s;
  s << "{\n"
    << in << "\"file\": " << json_string(r.file) << ",\n"
    << in << "\"hexes\": " << q.hexes << ",\n"
    << in << "\"vertices\": " << q.vertices << ",\n"
    << in << "\"inverted\": " << q.inverted << ",\n"
    << in << "\"msj\": " << json_number(q.msj) << ",\n"
    << in << "\"asj\": " << json_number(q.asj) << ",\n"
    << in << "\"certified\": " << (r.certificate.all_valid() ? "true" : "false") << ",\n"
    << in << "\"certified_valid\": " << r.certificate.certified_valid() << ",\n"
    << in << "\"not_certified\": [";
  for(std::size_t i = 0; i < r.certificate.not_certified.size(); ++i)
    s << (i ? ", " : "") << r.certificate.not_certified[i];
  s << "],\n"
    << in << "\"histogram\": {\"min\": -1, \"max\": 1, \"bins\": " << Q::histogram_bins << ", \"counts\": [";
  for(int k = 0; k < Q::histogram_bins; ++k)
    s << (k ? ", " : "") << q.histogram[k];
  s << "]}";
  if(!r.worst.empty())
  {
    s << ",\n" << in << "\"worst\": [";
    for(std::size_t i = 0; i < r.worst.size(); ++i)
    {
      const Worst_element& w = r.worst[i];
      s << (i ? ",\n" : "\n") << in << "  {\"id\": " << w.id << ", \"scaled_jacobian\": " << json_number(w.scaled_jacobian)
        << ", \"centre\": [" << json_number(w.centre[0]) << ", " << json_number(w.centre[1]) << ", "
        << json_number(w.centre[2]) << "]}";
    }
    s << "\n" << in << "]";
  }
  if(with_output_fields || r.seconds >= 0.)
    s << ",\n" << in << "\"seconds\": " << (r.seconds >= 0. ? json_number(r.seconds) : "null");
  if(with_output_fields)
  {
    s << ",\n" << in << "\"surface_error\": " << (r.surface_error >= 0. ? json_number(r.surface_error) : "null");
    s << ",\n" << in << "\"time_limit_reached\": " << (r.time_limit_reached ? "true" : "false");
    s << ",\n" << in << "\"interrupted\": " << (r.interrupted ? "true" : "false");
    s << ",\n" << in << "\"warnings\": [";
    for(std::size_t i = 0; i < r.warnings.size(); ++i) s << (i ? ", " : "") << json_string(r.warnings[i]);
    s << "]";
    s << ",\n" << in << "\"unresolved\": [";
    for(std::size_t i = 0; i < r.unresolved.size(); ++i)
    {
      const auto& e = r.unresolved[i];
      static const char* reasons[] = {"locked", "region_exhausted", "time_limit", "constrained"};
      s << (i ? ", " : "") << "{\"hex\": " << e.hex << ", \"scaled_jacobian\": " << json_number(e.scaled_jacobian)
        << ", \"reason\": \"" << reasons[int(e.reason)] << "\", \"details\": " << json_string(e.details) << "}";
    }
    s << "]";
    s << ",\n" << in << "\"off_surface\": [";
    for(std::size_t i = 0; i < r.off_surface.size(); ++i)
    {
      const auto& o = r.off_surface[i];
      s << (i ? ", " : "") << "{\"vertex\": " << o.vertex << ", \"distance\": " << json_number(o.distance)
        << ", \"allowed\": " << json_number(o.allowed) << ", \"local_length\": " << json_number(o.local_length) << "}";
    }
    s << "]";
  }
  s << "\n" << indent << "}";
  return s.str();
}

/// {"input": {...}, "output": {...}}: `output` only when there is one.
/// Histogram bin k counts scaled Jacobians in [-1 + 0.1 k, -1 + 0.1 (k+1)).
inline std::string json_report(const Mesh_report& input, const Mesh_report* output)
{
  std::ostringstream s;
  s << "{\n  \"input\": " << json_mesh_report(input, false, "  ");
  if(output)
    s << ",\n  \"output\": " << json_mesh_report(*output, true, "  ");
  s << "\n}\n";
  return s.str();
}

inline std::string xml_escape(const std::string& s)
{
  std::string r;
  for(char c : s)
  {
    switch(c)
    {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

inline std::string file_name_of(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// An SVG bar chart of the scaled Jacobian histogram: one bar per bin
/// (before, and after beside it when there is an output), on a logarithmic
/// count axis so that a handful of inverted elements stay visible next to
/// tens of thousands of good ones; the count is written above each bar.
inline std::string histogram_svg(const Mesh_report& input, const Mesh_report* output)
{
  typedef CGAL::Hex_mesh_quality Q;
  const int W = 900, H = 500;
  const double left = 80, right = 20, top = 112, bottom = 62;
  const double pw = W - left - right, ph = H - top - bottom;
  const char* colour_before = "#4e79a7";
  const char* colour_after = "#f28e2b";

  std::size_t max_count = 1;
  for(std::size_t c : input.quality.histogram)
    max_count = (std::max)(max_count, c);
  if(output)
    for(std::size_t c : output->quality.histogram)
      max_count = (std::max)(max_count, c);
  // log axis: y(c) = log10(1 + c) / log_top, with headroom above the
  // highest bar for its count label
  const double log_top = (std::max)(1.12 * std::log10(1. + double(max_count)), 1.);
  auto y_of = [&](double c) { return top + ph - ph * std::log10(1. + c) / log_top; };
  auto x_of = [&](double sj) { return left + pw * (sj + 1.) / 2.; };

  std::ostringstream s;
  s << std::fixed << std::setprecision(1);
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" viewBox=\"0 0 " << W << " " << H << "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << W / 2 << "\" y=\"26\" text-anchor=\"middle\" font-size=\"18\" font-weight=\"bold\">"
    << "Scaled Jacobian histogram: " << xml_escape(file_name_of(input.file)) << "</text>\n";

  // legend
  auto legend = [&](double y, const char* colour, const std::string& what, const Mesh_report& r) {
    s << "<rect x=\"" << left << "\" y=\"" << y - 11 << "\" width=\"14\" height=\"14\" fill=\"" << colour << "\"/>\n";
    s << "<text x=\"" << left + 20 << "\" y=\"" << y << "\" font-size=\"13\">" << what << " ("
      << xml_escape(file_name_of(r.file)) << "): " << r.quality.hexes << " hexes, " << r.quality.inverted
      << " inverted, MSJ " << format_fixed(r.quality.msj, 3) << ", ASJ " << format_fixed(r.quality.asj, 3)
      << "</text>\n";
  };
  legend(52, colour_before, "before", input);
  if(output)
    legend(72, colour_after, "after", *output);

  // inverted region, with its legend entry below the others
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << x_of(0) - left << "\" height=\"" << ph
    << "\" fill=\"#fbe3e3\"/>\n";
  const double legend_y = output ? 92 : 72;
  s << "<rect x=\"" << left << "\" y=\"" << legend_y - 11 << "\" width=\"14\" height=\"14\" fill=\"#fbe3e3\" stroke=\"#b03030\"/>\n";
  s << "<text x=\"" << left + 20 << "\" y=\"" << legend_y << "\" font-size=\"13\" fill=\"#b03030\">"
    << "inverted elements: scaled Jacobian &lt; 0</text>\n";

  // y grid and ticks
  for(double t = 1; std::log10(1. + t) <= log_top; t *= 10)
  {
    const double y = y_of(t);
    s << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + pw << "\" y2=\"" << y
      << "\" stroke=\"#dddddd\"/>\n";
    s << "<text x=\"" << left - 8 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\" font-size=\"12\">"
      << (long long)(t) << "</text>\n";
  }
  s << "<text x=\"" << left - 8 << "\" y=\"" << y_of(0) + 4 << "\" text-anchor=\"end\" font-size=\"12\">0</text>\n";
  s << "<text transform=\"translate(20 " << top + ph / 2 << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">"
    << "number of hexahedra (log scale)</text>\n";

  // bars
  const double bin_w = pw / Q::histogram_bins;
  const int series = output ? 2 : 1;
  const double bar_w = (bin_w - 6) / series;
  for(int k = 0; k < Q::histogram_bins; ++k)
  {
    for(int j = 0; j < series; ++j)
    {
      const Mesh_report& r = j == 0 ? input : *output;
      const std::size_t c = r.quality.histogram[k];
      const double x = left + k * bin_w + 3 + j * bar_w;
      const double y = y_of(double(c));
      if(c > 0)
      {
        s << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << bar_w - 1 << "\" height=\"" << top + ph - y
          << "\" fill=\"" << (j == 0 ? colour_before : colour_after) << "\"><title>" << bin_label(k) << ": " << c
          << "</title></rect>\n";
        const double tx = x + bar_w / 2 + 3, ty = y - 3;
        s << "<text transform=\"translate(" << tx << " " << ty << ") rotate(-90)\" font-size=\"10\">" << c
          << "</text>\n";
      }
    }
  }

  // x axis
  s << "<line x1=\"" << left << "\" y1=\"" << top + ph << "\" x2=\"" << left + pw << "\" y2=\"" << top + ph
    << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\"" << top + ph
    << "\" stroke=\"black\"/>\n";
  for(int k = 0; k <= Q::histogram_bins; k += 2)
  {
    const double sj = -1. + 2. * k / Q::histogram_bins;
    const double x = x_of(sj);
    s << "<line x1=\"" << x << "\" y1=\"" << top + ph << "\" x2=\"" << x << "\" y2=\"" << top + ph + 5
      << "\" stroke=\"black\"/>\n";
    s << "<text x=\"" << x << "\" y=\"" << top + ph + 20 << "\" text-anchor=\"middle\" font-size=\"12\">"
      << format_fixed(sj, 1) << "</text>\n";
  }
  s << "<line x1=\"" << x_of(0) << "\" y1=\"" << top << "\" x2=\"" << x_of(0) << "\" y2=\"" << top + ph
    << "\" stroke=\"#b03030\" stroke-dasharray=\"4 3\"/>\n";
  s << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 16 << "\" text-anchor=\"middle\" font-size=\"13\">"
    << "scaled Jacobian (Verdict, 8 corners + centre), bins of 0.1</text>\n";
  s << "</svg>\n";
  return s.str();
}

} // namespace hexmesh_optimize

#endif // HMO_TOOLS_QUALITY_REPORT_H
