// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// hexmesh-optimize INPUT [OUTPUT] [options]
//
// Reads a hexahedral mesh, reports its quality, runs the optimisation stages
// and writes the result with the quality after. See --help and README.md.
//
// Layout: the command line is in hexmesh_optimize_options.h, the report
// (text, JSON, SVG) in quality_report.h; this file only sequences the steps.
// Optimisation stages are added to `run_stages()`.

#include "hexmesh_optimize_options.h"
#include "quality_report.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <cctype>
#include <chrono>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef CGAL::Indexed_hex_mesh<Kernel::Point_3> Mesh;
typedef std::chrono::steady_clock Clock;

const char* const program = "hexmesh-optimize";

double seconds_since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

int fail(const std::string& message)
{
  std::cerr << program << ": error: " << message << std::endl;
  return 1;
}

bool ends_with(const std::string& s, const std::string& suffix)
{
  if(s.size() < suffix.size())
    return false;
  for(std::size_t i = 0; i < suffix.size(); ++i)
    if(std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i])
      return false;
  return true;
}

/// The optimisation pipeline, run when an OUTPUT is given. Each stage
/// changes the vertex positions of `mesh` (never its connectivity), may print
/// progress to `log` and returns false with `error` set when it cannot go on.
bool run_stages(Mesh& /*mesh*/, const hexmesh_optimize::Hexmesh_optimize_options& options,
                std::ostream& log, std::string& /*error*/)
{
  if(!options.quiet)
    log << "\nno optimisation stage yet: the mesh is written unchanged\n";
  return true;
}

} // namespace

int main(int argc, char** argv)
{
  using namespace hexmesh_optimize;

  Hexmesh_optimize_options options;
  std::string error;
  switch(parse_options(argc, argv, options, error))
  {
    case Parse_result::help:
      std::cout << usage();
      return 0;
    case Parse_result::error:
      std::cerr << program << ": error: " << error << "\n\n" << usage();
      return 2;
    case Parse_result::run:
      break;
  }
  std::ostream& out = std::cout;

  try
  {
    // ---------------------------------------------------------- read
    const Clock::time_point read_start = Clock::now();
    Mesh mesh;
    CGAL::IO::Hex_mesh_io_error io_error;
    std::vector<std::string> warnings;
    const bool read = CGAL::IO::read_hex_mesh(options.input, mesh, &io_error, &warnings);
    for(const std::string& w : warnings)
      std::cerr << "warning: " << w << std::endl;
    if(!read)
      return fail(io_error.what());

    Mesh_report before;
    before.file = options.input;
    before.quality = CGAL::hex_mesh_quality(mesh);
    before.seconds = seconds_since(read_start);
    if(!options.quiet)
    {
      print_quality_report(out, "before", before);
      out << "  read + quality: " << format_fixed(before.seconds, 3) << " s\n" << std::flush;
    }

    // ---------------------------------------------------- optimise, write
    Mesh_report after;
    const bool has_output = !options.output.empty();
    if(has_output)
    {
      const Mesh input_mesh = mesh; // the reference of the surface error
      const Clock::time_point start = Clock::now();
      if(!run_stages(mesh, options, out, error))
        return fail(error);
      after.seconds = seconds_since(start);
      const std::vector<double> sj = CGAL::hex_mesh_scaled_jacobians(mesh);
      after.file = options.output;
      after.quality = CGAL::hex_mesh_quality(mesh);
      // Hausdorff distance between the output and input boundaries, relative
      // to the diagonal of the input's bounding box
      after.surface_error = CGAL::hex_mesh_surface_error(mesh, input_mesh);

      CGAL::IO::Hex_mesh_fields fields;
      if(ends_with(options.output, ".vtk") || ends_with(options.output, ".vtu"))
        fields.cell_scalars.push_back({"scaled_jacobian", sj});
      if(!CGAL::IO::write_hex_mesh(options.output, mesh, fields, &io_error))
        return fail(io_error.what());
      if(!options.quiet)
      {
        out << "\n";
        print_quality_report(out, "after", after);
        out << "  optimisation: " << format_fixed(after.seconds, 3) << " s\n" << std::flush;
      }
    }

    // ------------------------------------------------------- reports
    if(!options.report_json.empty() &&
       !write_text_file(options.report_json, json_report(before, has_output ? &after : nullptr), error))
      return fail(error);
    if(!options.histogram_svg.empty() &&
       !write_text_file(options.histogram_svg, histogram_svg(before, has_output ? &after : nullptr), error))
      return fail(error);
  }
  catch(const std::exception& e)
  {
    return fail(e.what());
  }
  return 0;
}
