// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Command line of hexmesh-optimize: the options struct and a table-driven
// parser. To add an option: add a field to `Hexmesh_optimize_options` and one
// entry to `option_table()` (name, value name or nullptr for a flag, help
// text, and what to do with the value; `parse_number()` checks numbers).

#ifndef HMO_TOOLS_HEXMESH_OPTIMIZE_OPTIONS_H
#define HMO_TOOLS_HEXMESH_OPTIMIZE_OPTIONS_H

#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/parameters.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace hexmesh_optimize {

struct Hexmesh_optimize_options
{
  std::string input;         ///< the mesh to read (required)
  std::string output;        ///< where to write the result; empty: report only
  std::string report_json;   ///< --report FILE.json
  std::string histogram_svg; ///< --histogram-svg FILE.svg
  bool quiet = false;        ///< --quiet: no report on standard output
  // optimisation (with OUTPUT): the whole pipeline unless --untangle
  bool untangle_only = false;     ///< --untangle: only remove the inverted elements
  bool paper_method = false;      ///< --method paper: the method of Xu & Chen alone
  /// --paper-recipe FILE: a published run's parameters (with --method paper)
  std::string paper_recipe_file;
  CGAL::Hexahedral_mesh_optimization::Paper_recipe paper_recipe;
  bool sharp_angle_given = false, target_msj_given = false; ///< given on the command line
  std::string reference;          ///< --reference SURFACE: the surface the boundary must stay on
  double sharp_angle = 165.;      ///< --sharp-angle DEG
  double crease_seed_angle = 180.; ///< --crease-seed-angle DEG
  double turn_focus_band = 0.15;   ///< --turn-focus-band X
  double reference_feature_angle = 150.; ///< --reference-feature-angle DEG
  double target_msj = 1.;         ///< --target-msj X (1: as high as it gets)
  double surface_tolerance = 0.005; ///< --surface-tolerance X (relative to the bbox diagonal)
  double local_surface_tolerance = -1.; ///< --local-surface-tolerance X (of the shortest edge at a vertex; < 0: none)
  double time_limit = 0.;         ///< --time-limit S: hard stop of the whole run; 0: none
  int threads = 0;                ///< --threads N; 0: every core
  bool asj_smoothing = true;      ///< --no-asj
  bool pull_back = true;          ///< --no-pull-back
  bool coarse_level = true;       ///< --no-coarse-level
  bool relax_surface = true;      ///< --frozen-surface
  bool check = false;             ///< --check: TetGen reference-volume check of the output
  std::size_t worst = 0;          ///< --worst N: list the N worst elements; 0: none
  /// --output-format FORMAT: the format of OUTPUT whatever its extension
  bool has_output_format = false;
  /// the format OUTPUT is written in: --output-format's, or that of its extension
  CGAL::IO::Hex_mesh_file_format output_format = CGAL::IO::Hex_mesh_file_format::medit;
};

/// One command-line option. `value_name` is nullptr for a flag; `apply`
/// stores the value (empty for a flag) and returns false with a message
/// when the value is not acceptable.
struct Option_spec
{
  const char* name;
  const char* value_name;
  const char* help;
  std::function<bool(Hexmesh_optimize_options&, const std::string& value, std::string& error)> apply;
};

/// Parses a finite number in [min, max] for option `name`.
inline bool parse_number(const std::string& name, const std::string& text, double min, double max,
                         double& value, std::string& error)
{
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if(text.empty() || end != begin + text.size() || errno == ERANGE || !std::isfinite(v))
  {
    error = "option " + name + ": '" + text + "' is not a number";
    return false;
  }
  if(v < min || v > max)
  {
    std::ostringstream s;
    s << "option " << name << ": " << text << " is outside [" << min << ", " << max << "]";
    error = s.str();
    return false;
  }
  value = v;
  return true;
}

/// Parses a non-negative whole number (digits only, at most `max`) for
/// option `name`.
inline bool parse_count(const std::string& name, const std::string& text, std::size_t max, std::size_t& value,
                        std::string& error)
{
  bool digits = !text.empty();
  for(char c : text)
    digits = digits && std::isdigit(static_cast<unsigned char>(c));
  if(!digits)
  {
    error = "option " + name + ": '" + text + "' is not a non-negative whole number";
    return false;
  }
  std::size_t v = 0;
  for(char c : text)
  {
    v = 10 * v + std::size_t(c - '0');
    if(v > max)
    {
      std::ostringstream s;
      s << "option " << name << ": " << text << " is larger than " << max;
      error = s.str();
      return false;
    }
  }
  value = v;
  return true;
}

/// Reads a recipe file (`Paper_recipe`): one `name value` (or `name = value`)
/// a line, the names those of the struct's fields, `#` starting a comment;
/// false with a message on an unknown name or a bad value.
inline bool read_paper_recipe(const std::string& path, CGAL::Hexahedral_mesh_optimization::Paper_recipe& r,
                              std::string& error)
{
  std::ifstream in(path);
  if(!in)
  {
    error = "option --paper-recipe: cannot read '" + path + "'";
    return false;
  }
  struct Field
  {
    const char* name;
    double* value;
    double min, max;
  };
  double global = r.global ? 1. : 0., steps = r.msj_in_steps ? 1. : 0., iterations = r.pull_back_iterations,
         rings = r.untangle_rings, big_step = r.untangle_big_step ? 1. : 0.;
  const Field fields[] = {{"sharp_angle", &r.sharp_angle, 0., 180.},
                          {"msj_sharp_angle", &r.msj_sharp_angle, 0., 180.},
                          {"alpha", &r.alpha, 0., 1e12},
                          {"beta", &r.beta, 0., 1e12},
                          {"xi", &r.xi, 0., 10.},
                          {"global", &global, 0., 1.},
                          {"untangle_rings", &rings, 1., 1e9},
                          {"untangle_big_step", &big_step, 0., 1.},
                          {"pull_back_below_alpha", &r.pull_back_below_alpha, 0., 1e12},
                          {"pull_back_iterations", &iterations, 0., 1e6},
                          {"target_msj", &r.target_msj, -1., 1.},
                          {"msj_in_steps", &steps, 0., 1.},
                          {"msj_alpha", &r.msj_alpha, 0., 1e12},
                          {"msj_beta", &r.msj_beta, 0., 1e12},
                          {"msj_xi", &r.msj_xi, 0., 10.}};
  std::string line;
  for(int number = 1; std::getline(in, line); ++number)
  {
    line = line.substr(0, line.find('#'));
    for(char& c : line) if(c == '=') c = ' ';
    std::istringstream words(line);
    std::string name, value, extra;
    if(!(words >> name)) continue;
    const std::string where = path + ":" + std::to_string(number);
    if(!(words >> value) || (words >> extra))
    {
      error = "option --paper-recipe: " + where + ": expected 'name value'";
      return false;
    }
    const Field* f = nullptr;
    for(const Field& c : fields) if(name == c.name) f = &c;
    if(f == nullptr)
    {
      error = "option --paper-recipe: " + where + ": unknown name '" + name + "'";
      return false;
    }
    if(!parse_number(where + " " + name, value, f->min, f->max, *f->value, error)) return false;
  }
  r.global = global != 0.;
  r.msj_in_steps = steps != 0.;
  r.pull_back_iterations = static_cast<int>(iterations);
  r.untangle_rings = static_cast<int>(rings);
  r.untangle_big_step = big_step != 0.;
  return true;
}

inline const std::vector<Option_spec>& option_table()
{
  typedef Hexmesh_optimize_options O;
  static const std::vector<Option_spec> table = {
    {"--report", "FILE.json",
     "write the quality before (and after, with OUTPUT) as a JSON object",
     [](O& o, const std::string& v, std::string&) { o.report_json = v; return true; }},
    {"--histogram-svg", "FILE.svg",
     "draw the scaled Jacobian histogram before (and after, with OUTPUT) as SVG",
     [](O& o, const std::string& v, std::string&) { o.histogram_svg = v; return true; }},
    {"--untangle", nullptr,
     "only untangle (barrier with the boundary fixed, edge-angle optimiser, then the barrier stage on what is left); "
     "default: the whole pipeline (untangle, pull-back, MSJ stages, ASJ smoothing)",
     [](O& o, const std::string&, std::string&) { o.untangle_only = true; return true; }},
    {"--method", "NAME",
     "'package' (default): the package's pipeline; 'paper': the method of Xu & Chen (2018) alone, as published "
     "(edge-angle untangling, SLIM pull-back, edge-angle MSJ stages, ASJ smoothing)",
     [](O& o, const std::string& v, std::string& e) {
       if(v != "package" && v != "paper") { e = "option --method: '" + v + "' is neither 'package' nor 'paper'"; return false; }
       o.paper_method = v == "paper";
       return true;
     }},
    {"--paper-recipe", "FILE",
     "with --method paper: the parameters of a published run, one 'name value' a line (names: the fields of "
     "Paper_recipe: sharp_angle, msj_sharp_angle, alpha, beta, xi, global, untangle_rings, untangle_big_step, pull_back_below_alpha, "
     "pull_back_iterations, target_msj, msj_in_steps, msj_alpha, msj_beta, msj_xi; 0/1 for flags); --sharp-angle and --target-msj override it "
     "(default: the generic recipe of the authors' scripts)",
     [](O& o, const std::string& v, std::string& e) {
       o.paper_recipe_file = v;
       return read_paper_recipe(v, o.paper_recipe, e);
     }},
    {"--target-msj", "X",
     "stop raising the minimum scaled Jacobian at X (default 1: as high as it gets)",
     [](O& o, const std::string& v, std::string& e) {
       o.target_msj_given = true;
       return parse_number("--target-msj", v, 0., 1., o.target_msj, e);
     }},
    {"--reference", "SURFACE",
     "triangle surface (.obj .off .ply .stl) the boundary must stay on (default: the input's boundary)",
     [](O& o, const std::string& v, std::string&) { o.reference = v; return true; }},
    {"--sharp-angle", "DEG",
     "dihedral angle below which a boundary edge is a feature (default 165)",
     [](O& o, const std::string& v, std::string& e) {
       o.sharp_angle_given = true;
       return parse_number("--sharp-angle", v, 0., 180., o.sharp_angle, e);
     }},
    {"--reference-feature-angle", "DEG",
     "with --reference: its edges below this dihedral angle are creases the boundary recovers (default 150; 0: off)",
     [](O& o, const std::string& v, std::string& e) { return parse_number("--reference-feature-angle", v, 0., 180., o.reference_feature_angle, e); }},
    {"--crease-seed-angle", "DEG",
     "quality stages: a crease starts only at an edge below DEG, the edges below the sharp angle only continue it (default 180: off)",
     [](O& o, const std::string& v, std::string& e) { return parse_number("--crease-seed-angle", v, 0., 180., o.crease_seed_angle, e); }},
    {"--turn-focus-band", "X",
     "quality stages: the turns' ASJ pass reshapes the elements below MSJ + X (default 0.15; 0.2: higher MSJ, more time)",
     [](O& o, const std::string& v, std::string& e) {
       if(!parse_number("--turn-focus-band", v, 0., 1., o.turn_focus_band, e)) return false;
       if(o.turn_focus_band > 0.) return true;
       e = "option --turn-focus-band: " + v + " is outside (0, 1]";
       return false;
     }},
    {"--surface-tolerance", "X",
     "largest surface error the quality stages may cause, relative to the bounding-box diagonal (default 0.005)",
     [](O& o, const std::string& v, std::string& e) {
       return parse_number("--surface-tolerance", v, 0., 1., o.surface_tolerance, e);
     }},
    {"--local-surface-tolerance", "X",
     "also keep the boundary around each boundary vertex within X times the shortest edge at it in the input (thin "
     "boundary layers; default: none); the vertices left farther than the tolerances allow are listed",
     [](O& o, const std::string& v, std::string& e) {
       return parse_number("--local-surface-tolerance", v, 0., 1e6, o.local_surface_tolerance, e);
     }},
    {"--time-limit", "SECONDS",
     "hard stop: after SECONDS of wall time from the start (reading included) the optimisation stops at its next "
     "safe point and the last checked state is written, never worse than the input (default: none; the stages end "
     "on convergence, so the output does not depend on the machine)",
     [](O& o, const std::string& v, std::string& e) { return parse_number("--time-limit", v, 0., 1e7, o.time_limit, e); }},
    {"--threads", "N",
     "number of threads (default: every core); the output is the same for any N",
     [](O& o, const std::string& v, std::string& e) {
       double n = 0.;
       if(!parse_number("--threads", v, 1., 1024., n, e)) return false;
       if(n != std::floor(n)) { e = "option --threads: '" + v + "' is not a whole number"; return false; }
       o.threads = int(n);
       return true;
     }},
    {"--frozen-surface", nullptr,
     "never relax the surface while untangling (alpha, beta stay at their start value)",
     [](O& o, const std::string&, std::string&) { o.relax_surface = false; return true; }},
    {"--no-pull-back", nullptr,
     "skip the inversion-free pull-back of a relaxed surface",
     [](O& o, const std::string&, std::string&) { o.pull_back = false; return true; }},
    {"--no-asj", nullptr,
     "skip the final smoothing of the average scaled Jacobian",
     [](O& o, const std::string&, std::string&) { o.asj_smoothing = false; return true; }},
    {"--no-coarse-level", nullptr,
     "do not optimise a mesh recognised as a 1->8 refinement at its coarse level first",
     [](O& o, const std::string&, std::string&) { o.coarse_level = false; return true; }},
    {"--check", nullptr,
     "check the output against the reference volume (TetGen): volume, boundary self-intersection, "
     "vertices outside; exit status 3 when the check fails",
     [](O& o, const std::string&, std::string&) { o.check = true; return true; }},
    {"--worst", "N",
     "list the N worst elements of the output (of the input without OUTPUT), worst first: id (0-based, the cell "
     "id of ParaView), scaled Jacobian and centre (mean of the 8 vertices); also in the --report JSON as "
     "\"worst\" (default 0: none)",
     [](O& o, const std::string& v, std::string& e) { return parse_count("--worst", v, 1000000000, o.worst, e); }},
    {"--output-format", "FORMAT",
     "write OUTPUT in FORMAT whatever its extension: mesh, vtk, vtk-binary, vtu, msh (= msh41), msh41, "
     "msh41-binary, msh22, msh22-binary, inp, exo (default: from the extension; .msh is 4.1 ASCII, .vtk ASCII)",
     [](O& o, const std::string& v, std::string& e) {
       std::string why;
       if(!CGAL::IO::parse_hex_mesh_file_format(v, o.output_format, &why))
       {
         e = "option --output-format: " + why;
         return false;
       }
       o.has_output_format = true;
       return true;
     }},
    {"--quiet", nullptr,
     "print only warnings and errors",
     [](O& o, const std::string&, std::string&) { o.quiet = true; return true; }},
  };
  return table;
}

inline std::string usage()
{
  std::ostringstream s;
  s << "usage: hexmesh-optimize INPUT [OUTPUT] [options]\n"
       "\n"
       "Reads a hexahedral mesh (MEDIT .mesh, VTK legacy .vtk, VTK XML .vtu, gmsh .msh,\n"
       "Abaqus .inp, Exodus II .exo/.e), prints\n"
       "its quality (hexahedra, vertices, inverted elements, minimum and average\n"
       "Verdict scaled Jacobian, histogram) and, when OUTPUT is given, writes the\n"
       "optimised mesh there with the quality after (.vtk/.vtu/.msh outputs carry the\n"
       "per-cell scaled Jacobian as the cell field \"scaled_jacobian\").\n"
       "Groups go where the output format has a place for them. Exodus II element block\n"
       "ids must be positive: MEDIT reference 0 (often on every element) becomes block 1,\n"
       "other references <= 0 the next ids no reference uses, with a warning.\n"
       "OUTPUT, --report and --histogram-svg are checked before any work: format (from the\n"
       "extension), folder, a file can be created there, groups the format can hold.\n"
       "\n"
       "options:\n";
  for(const Option_spec& o : option_table())
  {
    std::string left = std::string("  ") + o.name + (o.value_name ? std::string(" ") + o.value_name : "");
    if(left.size() < 28)
      left.resize(28, ' ');
    else
      left += "\n" + std::string(28, ' ');
    s << left << o.help << "\n";
  }
  s << "  -h, --help                  print this help and exit\n"
       "\n"
       "exit status: 0 success (with OUTPUT: every element of the output is certified\n"
       "valid, its Jacobian positive at the 8 corners and the centre by exact arithmetic), 1 the\n"
       "mesh could not be read, processed or written (an output that cannot be written is\n"
       "found before the work, and nothing is written), 2 bad command line or a --reference\n"
       "that does not fit the mesh (another frame or object; nothing is written), 3 --check\n"
       "failed, 4 elements of the output are still inverted or not certified valid (listed\n"
       "on standard error and in\n"
       "the JSON report), 5 the time limit stopped the stages (the output has no inverted\n"
       "element); 3, 4 and 5 write the output all the same, and 4 comes before 3 before 5;\n"
       "130 (SIGINT, Ctrl-C) or 143 (SIGTERM): interrupted, the stages stopped at their next\n"
       "safe point and the last checked state (never worse than the input) was written; a\n"
       "second signal ends the program at once, leaving the previous output file intact\n";
  return s.str();
}

/// whether `path` ends in `extension` (".json", ".svg"; any case)
inline bool has_extension(const std::string& path, const std::string& extension)
{
  if(path.size() < extension.size())
    return false;
  for(std::size_t i = 0; i < extension.size(); ++i)
    if(std::tolower(static_cast<unsigned char>(path[path.size() - extension.size() + i])) !=
       std::tolower(static_cast<unsigned char>(extension[i])))
      return false;
  return true;
}

enum class Parse_result { run, help, error };

/// Fills `options` from the command line. Options may come before or after
/// the files, as `--name VALUE` or `--name=VALUE`; `--` ends the options.
inline Parse_result parse_options(int argc, const char* const* argv, Hexmesh_optimize_options& options,
                                  std::string& error)
{
  std::vector<std::string> files;
  bool options_done = false;
  for(int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if(options_done || arg.size() < 2 || arg[0] != '-')
    {
      files.push_back(arg);
      continue;
    }
    if(arg == "--")
    {
      options_done = true;
      continue;
    }
    if(arg == "-h" || arg == "--help")
      return Parse_result::help;

    const std::size_t eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const Option_spec* spec = nullptr;
    for(const Option_spec& o : option_table())
      if(name == o.name)
        spec = &o;
    if(spec == nullptr)
    {
      error = "unknown option '" + name + "'";
      return Parse_result::error;
    }
    std::string value;
    if(spec->value_name != nullptr)
    {
      if(eq != std::string::npos)
        value = arg.substr(eq + 1);
      else if(i + 1 < argc)
        value = argv[++i];
      else
      {
        error = "option " + name + " needs a value (" + spec->value_name + ")";
        return Parse_result::error;
      }
      if(value.empty())
      {
        error = "option " + name + " needs a non-empty value (" + spec->value_name + ")";
        return Parse_result::error;
      }
    }
    else if(eq != std::string::npos)
    {
      error = "option " + name + " takes no value";
      return Parse_result::error;
    }
    if(!spec->apply(options, value, error))
      return Parse_result::error;
  }

  if(files.empty())
  {
    error = "no input mesh given";
    return Parse_result::error;
  }
  if(files.size() > 2)
  {
    error = "too many file arguments (expected INPUT [OUTPUT]): '" + files[2] + "'";
    return Parse_result::error;
  }
  if(!options.paper_recipe_file.empty() && !options.paper_method)
  {
    error = "option --paper-recipe needs --method paper";
    return Parse_result::error;
  }
  if(options.paper_method) // the recipe's angle and target unless given here
  {
    if(!options.sharp_angle_given) options.sharp_angle = options.paper_recipe.sharp_angle;
    if(!options.target_msj_given) options.target_msj = options.paper_recipe.target_msj;
  }
  options.input = files[0];
  if(files.size() == 2)
  {
    options.output = files[1];
    // checked now rather than after a long optimisation; the format of the
    // extension is the one CGAL::IO::write_hex_mesh() would choose
    std::string why;
    if(!options.has_output_format &&
       !CGAL::IO::hex_mesh_file_format_from_extension(options.output, options.output_format, &why))
    {
      error = "output '" + options.output + "': " + why + " (or give --output-format)";
      return Parse_result::error;
    }
  }
  // the reports are JSON and SVG whatever their names: a name that says
  // otherwise (report.txt, histogram.png) is a mistake found before the work
  struct Report_path
  {
    const char* option;
    const std::string* path;
    const char* extension;
  };
  const Report_path reports[] = {{"--report", &options.report_json, ".json"},
                                 {"--histogram-svg", &options.histogram_svg, ".svg"}};
  for(const Report_path& r : reports)
    if(!r.path->empty() && !has_extension(*r.path, r.extension))
    {
      error = std::string("option ") + r.option + ": '" + *r.path + "' must end in " + r.extension;
      return Parse_result::error;
    }
  return Parse_result::run;
}

} // namespace hexmesh_optimize

#endif // HMO_TOOLS_HEXMESH_OPTIMIZE_OPTIONS_H
