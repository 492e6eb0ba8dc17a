// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The compiled part of the Python package `hexmesh_optimization`
// (python/hexmesh_optimization/__init__.py re-exports it and adds the meshio
// interoperability): reading and writing meshes, the scaled Jacobian and the
// quality report, and the three optimisation functions, on numpy arrays.
//
// A mesh is a pair of arrays: `points` (float64, N x 3) and `hexes`
// (integers, M x 8, the MEDIT/VTK vertex order, numbered from 0). Every
// function validates them as the readers validate a file
// (`CGAL::validate_hex_mesh`) and raises ValueError with the same message;
// a file that cannot be opened raises OSError (FileNotFoundError when it
// does not exist), one that cannot be read ValueError, with the tool's
// one-line messages ("file:line: problem").

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/validate_hex_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/hex_mesh_surface_error.h>
#include <CGAL/improve_hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Indexed_hex_mesh<Point> Mesh;
typedef CGAL::Surface_mesh<Point> Surface;
namespace HMO = CGAL::Hexahedral_mesh_optimization;

[[noreturn]] void raise(PyObject* type, const std::string& message)
{
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

// ------------------------------------------------------------ arrays <-> mesh

/// the mesh of `points` (N x 3 numbers) and `hexes` (M x 8 integers),
/// validated as a file would be; ValueError otherwise
Mesh mesh_from_arrays(const py::array& points, const py::array& hexes)
{
  if(points.ndim() != 2 || points.shape(1) != 3)
    raise(PyExc_ValueError, "points: expected an array of shape (N, 3), got " +
                              std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                                points.shape(), points.shape() + points.ndim()))))));
  if(hexes.ndim() != 2 || hexes.shape(1) != 8)
    raise(PyExc_ValueError, "hexes: expected an array of shape (M, 8), got " +
                              std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                                hexes.shape(), hexes.shape() + hexes.ndim()))))));
  const char kind = hexes.dtype().kind();
  if(kind != 'i' && kind != 'u')
    raise(PyExc_ValueError, std::string("hexes: expected integer vertex indices, got dtype ") +
                              std::string(py::str(hexes.dtype())));
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if(!p)
    raise(PyExc_ValueError, "points: cannot be read as float64 numbers");
  const auto h = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(hexes);
  Mesh mesh;
  const py::ssize_t n = p.shape(0), m = h.shape(0);
  mesh.points.reserve(std::size_t(n));
  const double* pd = p.data();
  for(py::ssize_t i = 0; i < n; ++i) mesh.points.emplace_back(pd[3 * i], pd[3 * i + 1], pd[3 * i + 2]);
  mesh.hexahedra.resize(std::size_t(m));
  const std::int64_t* hd = h.data();
  for(py::ssize_t i = 0; i < m; ++i)
    for(int k = 0; k < 8; ++k)
    {
      const std::int64_t v = hd[8 * i + k];
      if(v < 0)
        raise(PyExc_ValueError, "hexes[" + std::to_string(i) + "]: vertex index " + std::to_string(v) +
                                  " is negative (indices are numbered from 0)");
      mesh.hexahedra[std::size_t(i)][std::size_t(k)] = std::size_t(v);
    }
  if(mesh.hexahedra.empty())
    raise(PyExc_ValueError, "hexes: the mesh has no hexahedron");
  std::string problem;
  if(!CGAL::validate_hex_mesh(mesh, &problem))
    raise(PyExc_ValueError, problem);
  return mesh;
}

py::array_t<double> points_array(const Mesh& mesh)
{
  py::array_t<double> a({py::ssize_t(mesh.points.size()), py::ssize_t(3)});
  double* d = a.mutable_data();
  for(std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    d[3 * i] = mesh.points[i].x();
    d[3 * i + 1] = mesh.points[i].y();
    d[3 * i + 2] = mesh.points[i].z();
  }
  return a;
}

py::array_t<std::int64_t> hexes_array(const Mesh& mesh)
{
  py::array_t<std::int64_t> a({py::ssize_t(mesh.hexahedra.size()), py::ssize_t(8)});
  std::int64_t* d = a.mutable_data();
  for(std::size_t i = 0; i < mesh.hexahedra.size(); ++i)
    for(int k = 0; k < 8; ++k) d[8 * i + k] = std::int64_t(mesh.hexahedra[i][k]);
  return a;
}

py::array_t<double> double_array(const std::vector<double>& v)
{
  py::array_t<double> a(py::ssize_t(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

std::string path_string(const py::object& path)
{
  return py::str(py::module_::import("os").attr("fspath")(path));
}

/// OSError when `fname` cannot be opened for reading (FileNotFoundError
/// when it does not exist), with the reader's message
void require_readable(const std::string& fname, const std::string& what)
{
  errno = 0;
  if(std::FILE* f = std::fopen(fname.c_str(), "rb"))
  {
    std::fclose(f);
    return;
  }
  PyObject* type = errno == ENOENT ? PyExc_FileNotFoundError : errno == EACCES ? PyExc_PermissionError : PyExc_OSError;
  raise(type, what + (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
}

// ------------------------------------------------------------------ reading

py::tuple read_mesh(const py::object& path)
{
  const std::string fname = path_string(path);
  require_readable(fname, fname + ": cannot open the file");
  Mesh mesh;
  CGAL::IO::Hex_mesh_io_error error;
  std::vector<std::string> warnings;
  if(!CGAL::IO::read_hex_mesh(fname, mesh, &error, &warnings))
    raise(PyExc_ValueError, error.what());
  if(!warnings.empty())
  {
    py::object warn = py::module_::import("warnings").attr("warn");
    for(const std::string& w : warnings) warn(fname + ": " + w, py::handle(PyExc_UserWarning), 2);
  }
  return py::make_tuple(points_array(mesh), hexes_array(mesh));
}

/// the per-hexahedron fields of a `cell_data` dict (None: no field), one
/// number per hexahedron each
CGAL::IO::Hex_mesh_fields cell_fields(const py::object& cell_data, std::size_t hexahedra)
{
  CGAL::IO::Hex_mesh_fields fields;
  if(cell_data.is_none()) return fields;
  for(const auto& item : py::cast<py::dict>(cell_data))
  {
    const std::string name = py::str(item.first);
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(item.second);
    if(!values || values.ndim() != 1 || std::size_t(values.shape(0)) != hexahedra)
      raise(PyExc_ValueError, "cell_data['" + name + "']: expected one number per hexahedron (" +
                                std::to_string(hexahedra) + ")");
    fields.cell_scalars.push_back({name, std::vector<double>(values.data(), values.data() + values.shape(0))});
  }
  return fields;
}

void write_mesh(const py::object& path, const py::array& points, const py::array& hexes, const py::object& cell_data,
                const py::object& format)
{
  const std::string fname = path_string(path);
  const Mesh mesh = mesh_from_arrays(points, hexes);
  const CGAL::IO::Hex_mesh_fields fields = cell_fields(cell_data, mesh.hexahedra.size());
  CGAL::IO::Hex_mesh_io_error error;
  bool written = false;
  if(!format.is_none())
  {
    CGAL::IO::Hex_mesh_file_format f;
    std::string why;
    if(!CGAL::IO::parse_hex_mesh_file_format(std::string(py::str(format)), f, &why))
      raise(PyExc_ValueError, "format: " + why);
    written = CGAL::IO::write_hex_mesh_as(f, fname, mesh, fields, &error);
  }
  else
  {
    std::string why;
    if(HMO::internal::io::hex_mesh_format(fname, why) == HMO::internal::io::Hex_mesh_format::unknown)
      raise(PyExc_ValueError, fname + ": " + why);
    written = CGAL::IO::write_hex_mesh(fname, mesh, fields, &error);
  }
  if(!written)
    raise(PyExc_OSError, error.what()); // the mesh and the format were checked: the file system refused
}

// ------------------------------------------------------- a mesh with its groups

/// A mesh read from a file with everything the file held (references,
/// names, sets, ids, MEDIT sections): the command line
/// (`python -m hexmesh_optimization`) optimises its points and writes it
/// with its groups, as hexmesh-optimize does. Not a public API.
struct Mesh_file
{
  Mesh mesh;
  std::vector<std::string> warnings; // the reader's
};

Mesh_file read_mesh_file(const py::object& path)
{
  const std::string fname = path_string(path);
  require_readable(fname, fname + ": cannot open the file");
  Mesh_file f;
  CGAL::IO::Hex_mesh_io_error error;
  if(!CGAL::IO::read_hex_mesh(fname, f.mesh, &error, &f.warnings))
    raise(PyExc_ValueError, error.what());
  return f;
}

/// the format of `path`: `format` when not None, else by the extension; ValueError otherwise
CGAL::IO::Hex_mesh_file_format output_format(const std::string& fname, const py::object& format)
{
  CGAL::IO::Hex_mesh_file_format f;
  std::string why;
  if(!format.is_none())
  {
    if(!CGAL::IO::parse_hex_mesh_file_format(std::string(py::str(format)), f, &why))
      raise(PyExc_ValueError, "format: " + why);
  }
  else if(!CGAL::IO::hex_mesh_file_format_from_extension(fname, f, &why))
    raise(PyExc_ValueError, fname + ": " + why);
  return f;
}

/// check_hex_mesh_output(): OSError when `path` cannot be written, else the
/// warnings about the groups the format does not hold
std::vector<std::string> check_mesh_file_output(const Mesh_file& f, const py::object& path, const py::object& format)
{
  const std::string fname = path_string(path);
  CGAL::IO::Hex_mesh_io_error error;
  std::vector<std::string> warnings;
  if(!CGAL::IO::check_hex_mesh_output(output_format(fname, format), fname, f.mesh, &error, &warnings))
    raise(PyExc_OSError, error.what());
  return warnings;
}

/// writes the mesh with `points` (the optimised ones) and its groups
void write_mesh_file(const Mesh_file& f, const py::object& path, const py::array& points, const py::object& cell_data,
                     const py::object& format)
{
  const std::string fname = path_string(path);
  const CGAL::IO::Hex_mesh_file_format ff = output_format(fname, format);
  Mesh mesh = f.mesh;
  const Mesh moved = mesh_from_arrays(points, hexes_array(f.mesh));
  if(moved.points.size() != mesh.points.size())
    raise(PyExc_ValueError, "points: expected " + std::to_string(mesh.points.size()) + " points");
  mesh.points = moved.points;
  const CGAL::IO::Hex_mesh_fields fields = cell_fields(cell_data, mesh.hexahedra.size());
  CGAL::IO::Hex_mesh_io_error error;
  if(!CGAL::IO::write_hex_mesh_as(ff, fname, mesh, fields, &error))
    raise(PyExc_OSError, error.what());
}

/// probe_output_file(): OSError when no file can be created at `path`
void check_output_file(const py::object& path)
{
  const std::string fname = path_string(path);
  std::string why;
  if(!HMO::internal::io::probe_output_file(fname, why))
    raise(PyExc_OSError, fname + ": " + why);
}

// ------------------------------------------------------------------ quality

py::array_t<double> scaled_jacobian(const py::array& points, const py::array& hexes)
{
  return double_array(CGAL::hex_mesh_scaled_jacobians(mesh_from_arrays(points, hexes)));
}

py::dict quality_dict(const CGAL::Hex_mesh_quality& q, const HMO::Validity_certificate& c)
{
  py::dict d;
  d["hexes"] = q.hexes;
  d["vertices"] = q.vertices;
  d["inverted"] = q.inverted;
  d["msj"] = q.msj;
  d["asj"] = q.asj;
  std::vector<double> edges;
  for(int k = 0; k <= CGAL::Hex_mesh_quality::histogram_bins; ++k)
    edges.push_back(CGAL::Hex_mesh_quality::bin_lower(k));
  py::array_t<std::int64_t> counts(py::ssize_t(q.histogram.size()));
  for(std::size_t k = 0; k < q.histogram.size(); ++k) counts.mutable_data()[k] = std::int64_t(q.histogram[k]);
  d["histogram"] = counts;
  d["histogram_edges"] = double_array(edges);
  d["certified_valid"] = c.certified_valid();
  d["not_certified"] = c.not_certified;
  return d;
}

py::dict quality(const py::array& points, const py::array& hexes)
{
  const Mesh mesh = mesh_from_arrays(points, hexes);
  return quality_dict(CGAL::hex_mesh_quality(mesh), CGAL::hex_mesh_validity_certificate(mesh));
}

// ------------------------------------------------------------- optimisation

/// The named parameters of the three functions, from keyword arguments.
/// The defaults are the library's own: read by its parameter readers from
/// `parameters::default_values()`, so that they cannot drift apart.
struct Options
{
  double sharp_angle, reference_feature_angle, alpha, beta, xi;
  bool relax_surface;
  int local_iterations, number_of_iterations;
  bool barrier_fallback;
  double target_msj, surface_tolerance, crease_seed_angle, turn_focus_band;
  double local_surface_tolerance = -1.; // none
  bool pull_back, asj_smoothing, edge_angle_stages, coarse_level_start;
  HMO::Method method = HMO::Method::package;
  double time_limit = std::numeric_limits<double>::infinity();
  int threads = 0;

  Options()
  {
    HMO::internal::Untangle_settings u;
    std::vector<HMO::internal::Vec3> rp;
    std::vector<HMO::internal::Tri> rt;
    std::vector<std::array<std::size_t, 2> > rc;
    HMO::internal::read_untangle_parameters(CGAL::parameters::default_values(), u, rp, rt, rc);
    HMO::internal::Quality_settings q;
    HMO::internal::read_quality_parameters(CGAL::parameters::default_values(), u, q);
    sharp_angle = u.sharp_angle;
    reference_feature_angle = u.reference_feature_angle;
    alpha = u.alpha;
    beta = u.beta;
    xi = u.xi;
    relax_surface = u.relax_surface;
    local_iterations = u.local_iterations;
    number_of_iterations = u.max_rounds;
    barrier_fallback = u.barrier_fallback;
    target_msj = q.target_msj;
    surface_tolerance = q.surface_tolerance;
    pull_back = q.pull_back;
    asj_smoothing = q.asj_smoothing;
    edge_angle_stages = q.schedule.msj_stage_edge_angle_passes > 0;
    coarse_level_start = q.schedule.coarse_level_start;
    crease_seed_angle = q.schedule.crease_seed_angle;
    turn_focus_band = q.schedule.turn_focus_band;
  }
};

enum class Function { untangle, improve_quality, optimize };

const char* function_name(Function f)
{
  return f == Function::untangle ? "untangle" : f == Function::improve_quality ? "improve_quality" : "optimize";
}

/// the keyword arguments each function accepts (besides `reference` and `progress`)
const std::set<std::string>& accepted_options(Function f)
{
  static const std::set<std::string> untangle{"sharp_angle", "reference_feature_angle", "alpha", "beta", "xi", "relax_surface",
                                              "local_iterations", "number_of_iterations", "barrier_fallback",
                                              "surface_tolerance", "local_surface_tolerance", "method", "time_limit",
                                              "threads"};
  static const std::set<std::string> quality = [] {
    std::set<std::string> s = untangle;
    s.insert({"target_msj", "pull_back", "asj_smoothing", "edge_angle_stages", "coarse_level_start", "crease_seed_angle", "turn_focus_band"});
    return s;
  }();
  return f == Function::untangle ? untangle : quality;
}

double finite_number(const std::string& name, const py::handle& v, double min, double max)
{
  if(!py::isinstance<py::float_>(v) && !py::isinstance<py::int_>(v))
    raise(PyExc_TypeError, name + ": expected a number, got " + std::string(py::str(py::type::of(v).attr("__name__"))));
  const double x = py::cast<double>(v);
  if(!std::isfinite(x) || x < min || x > max)
    raise(PyExc_ValueError, name + ": " + std::string(py::repr(v)) + " is outside [" + std::to_string(min) + ", " +
                              std::to_string(max) + "]");
  return x;
}

int whole_number(const std::string& name, const py::handle& v, int min)
{
  if(!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    raise(PyExc_TypeError, name + ": expected an integer, got " + std::string(py::str(py::type::of(v).attr("__name__"))));
  const long long x = py::cast<long long>(v);
  if(x < min || x > 1000000000LL)
    raise(PyExc_ValueError, name + ": " + std::to_string(x) + " is outside [" + std::to_string(min) + ", 1e9]");
  return int(x);
}

bool boolean(const std::string& name, const py::handle& v)
{
  if(!py::isinstance<py::bool_>(v))
    raise(PyExc_TypeError, name + ": expected True or False, got " + std::string(py::str(py::type::of(v).attr("__name__"))));
  return py::cast<bool>(v);
}

Options read_options(Function f, const py::kwargs& kwargs)
{
  Options o;
  const std::set<std::string>& accepted = accepted_options(f);
  bool edge_angle_given = false, coarse_level_given = false;
  for(const auto& item : kwargs)
  {
    const std::string name = py::str(item.first);
    if(accepted.count(name) == 0)
      raise(PyExc_TypeError, std::string(function_name(f)) + "() got an unexpected keyword argument '" + name + "'");
    const py::handle v = item.second;
    if(name == "sharp_angle") o.sharp_angle = finite_number(name, v, 0., 180.);
    else if(name == "reference_feature_angle") o.reference_feature_angle = finite_number(name, v, 0., 180.);
    else if(name == "crease_seed_angle") o.crease_seed_angle = finite_number(name, v, 0., 180.);
    else if(name == "turn_focus_band")
    {
      o.turn_focus_band = finite_number(name, v, 0., 1.);
      if(!(o.turn_focus_band > 0.)) raise(PyExc_ValueError, name + ": " + std::string(py::repr(v)) + " is outside (0, 1]");
    }
    else if(name == "alpha") o.alpha = finite_number(name, v, 0., 1e12);
    else if(name == "beta") o.beta = finite_number(name, v, 0., 1e12);
    else if(name == "xi") o.xi = finite_number(name, v, 0., 10.);
    else if(name == "relax_surface") o.relax_surface = boolean(name, v);
    else if(name == "local_iterations") o.local_iterations = whole_number(name, v, 1);
    else if(name == "number_of_iterations") o.number_of_iterations = whole_number(name, v, 0);
    else if(name == "barrier_fallback") o.barrier_fallback = boolean(name, v);
    else if(name == "target_msj") o.target_msj = finite_number(name, v, -1., 1.);
    else if(name == "surface_tolerance") o.surface_tolerance = finite_number(name, v, 0., 1.);
    else if(name == "local_surface_tolerance")
    {
      if(!v.is_none()) o.local_surface_tolerance = finite_number(name, v, 0., 1e6);
    }
    else if(name == "pull_back") o.pull_back = boolean(name, v);
    else if(name == "asj_smoothing") o.asj_smoothing = boolean(name, v);
    else if(name == "edge_angle_stages") { o.edge_angle_stages = boolean(name, v); edge_angle_given = true; }
    else if(name == "coarse_level_start") { o.coarse_level_start = boolean(name, v); coarse_level_given = true; }
    else if(name == "time_limit") { if(!v.is_none()) o.time_limit = finite_number(name, v, 0., 1e9); }
    else if(name == "threads") o.threads = whole_number(name, v, 0);
    else if(name == "method")
    {
      const std::string m = py::isinstance<py::str>(v) ? std::string(py::str(v)) : std::string();
      if(m == "package") o.method = HMO::Method::package;
      else if(m == "paper") o.method = HMO::Method::paper;
      else raise(PyExc_ValueError, "method: expected 'package' or 'paper', got " + std::string(py::repr(v)));
    }
  }
  // as in the library: the paper's method runs the edge-angle optimiser in its MSJ stages
  if(!edge_angle_given) o.edge_angle_stages = o.method == HMO::Method::paper;
  if(!coarse_level_given) o.coarse_level_start = o.method != HMO::Method::paper;
  return o;
}

/// The visitor handed to the optimisation: calls `progress(stage, value)`
/// (the number of elements to fix when a stage starts and after its rounds,
/// 1.0 when it is done) with the GIL held, and checks for Ctrl-C. An
/// exception, from the callable or KeyboardInterrupt, sets the stop flag:
/// the stages stop at their next safe point and it is raised afterwards.
struct Python_visitor : HMO::Default_optimization_visitor
{
  py::object progress; // None: no callable
  std::atomic<bool>* stop = nullptr;
  std::unique_ptr<py::error_already_set> error;

  // `count` < 0: the stage is done (1.0 is passed)
  void notify(const std::string& stage, long long count)
  {
    if(error) return;
    py::gil_scoped_acquire gil; // before any Python object is made
    try
    {
      if(PyErr_CheckSignals() != 0) throw py::error_already_set();
      if(!progress.is_none())
      {
        if(count < 0) progress(stage, py::float_(1.));
        else progress(stage, py::int_(count));
      }
    }
    catch(py::error_already_set& e)
    {
      error.reset(new py::error_already_set(std::move(e)));
      stop->store(true);
    }
  }
  void stage_started(const std::string& name, std::size_t bad) { notify(name, (long long)bad); }
  void round_finished(const std::string& stage, int, std::size_t left) { notify(stage, (long long)left); }
  void stage_finished(const HMO::Stage_report& r) { notify(r.name, -1); }
};

py::dict result_dict(const HMO::Optimization_result& r)
{
  py::dict d;
  d["success"] = r.success;
  d["kept_input"] = r.kept_input;
  d["inverted_before"] = r.inverted_before;
  d["inverted_after"] = r.inverted_after;
  d["msj_before"] = r.msj_before;
  d["msj_after"] = r.msj_after;
  d["asj_before"] = r.asj_before;
  d["asj_after"] = r.asj_after;
  d["surface_error"] = r.surface_error;
  d["seconds"] = r.seconds;
  d["time_limit_reached"] = r.time_limit_reached;
  d["interrupted"] = r.interrupted;
  d["warnings"] = r.warnings;
  py::list unresolved;
  for(const HMO::Unresolved_element& u : r.unresolved)
  {
    py::dict e;
    e["hex"] = u.hex;
    e["scaled_jacobian"] = u.scaled_jacobian;
    e["reason"] = u.reason == HMO::Unresolved_element::locked             ? "locked"
                  : u.reason == HMO::Unresolved_element::region_exhausted ? "region_exhausted"
                  : u.reason == HMO::Unresolved_element::constrained      ? "constrained"
                                                                          : "time_limit";
    e["details"] = u.details;
    unresolved.append(e);
  }
  d["unresolved"] = unresolved;
  py::list off_surface;
  for(const HMO::Off_surface_vertex& o : r.off_surface)
  {
    py::dict e;
    e["vertex"] = o.vertex;
    e["distance"] = o.distance;
    e["allowed"] = o.allowed;
    e["local_length"] = o.local_length;
    off_surface.append(e);
  }
  d["off_surface"] = off_surface;
  py::dict certificate;
  certificate["hexes"] = r.certificate.hexes;
  certificate["certified_valid"] = r.certificate.certified_valid();
  certificate["not_certified"] = r.certificate.not_certified;
  d["certificate"] = certificate;
  py::list stages;
  for(const HMO::Stage_report& s : r.stages)
  {
    py::dict e;
    e["name"] = s.name;
    e["inverted_before"] = s.inverted_before;
    e["inverted_after"] = s.inverted_after;
    e["msj_after"] = s.msj_after;
    e["seconds"] = s.seconds;
    e["rounds"] = s.rounds;
    e["details"] = s.details;
    stages.append(e);
  }
  d["stages"] = stages;
  return d;
}

/// `reference`: None, a path, or a pair (vertices N x 3, faces F x k)
bool reference_surface(const py::object& reference, Surface& surface)
{
  if(reference.is_none()) return false;
  std::string error;
  if(py::isinstance<py::str>(reference) || py::hasattr(reference, "__fspath__"))
  {
    const std::string fname = path_string(reference);
    require_readable(fname, "cannot open reference surface '" + fname + "'");
    if(!CGAL::IO::read_reference_surface(fname, surface, &error)) raise(PyExc_ValueError, error);
    return true;
  }
  if(!py::isinstance<py::sequence>(reference) || py::len(reference) != 2)
    raise(PyExc_TypeError, "reference: expected None, a path or a pair (vertices, faces) of arrays");
  const py::sequence pair = py::cast<py::sequence>(reference);
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(pair[0]);
  const py::array f_any = py::array::ensure(pair[1]);
  if(!v || v.ndim() != 2 || v.shape(1) != 3)
    raise(PyExc_ValueError, "reference vertices: expected an array of shape (N, 3)");
  if(!f_any || f_any.ndim() != 2 || f_any.shape(1) < 3 || (f_any.dtype().kind() != 'i' && f_any.dtype().kind() != 'u'))
    raise(PyExc_ValueError, "reference faces: expected an integer array of shape (F, 3) or (F, 4)");
  const auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(f_any);
  std::vector<Point> points;
  for(py::ssize_t i = 0; i < v.shape(0); ++i) points.emplace_back(v.at(i, 0), v.at(i, 1), v.at(i, 2));
  std::vector<std::vector<std::size_t> > polygons(std::size_t(f.shape(0)));
  for(py::ssize_t i = 0; i < f.shape(0); ++i)
    for(py::ssize_t k = 0; k < f.shape(1); ++k)
    {
      const std::int64_t x = f.at(i, k);
      if(x < 0)
        raise(PyExc_ValueError, "reference surface: face " + std::to_string(i) + " uses vertex " + std::to_string(x) +
                                  ", negative (numbered from 0)");
      polygons[std::size_t(i)].push_back(std::size_t(x));
    }
  if(!CGAL::IO::polygon_soup_to_reference_surface(points, polygons, surface, "reference surface", &error))
    raise(PyExc_ValueError, error);
  return true;
}

template <class NP>
HMO::Optimization_result call(Function f, Mesh& mesh, const NP& np)
{
  switch(f)
  {
  case Function::untangle: return CGAL::untangle_hex_mesh(mesh, np);
  case Function::improve_quality: return CGAL::improve_hex_mesh_quality(mesh, np);
  default: return CGAL::optimize_hex_mesh(mesh, np);
  }
}

py::tuple run(Function f, const py::array& points, const py::array& hexes, const py::object& reference,
              const py::object& progress, const py::kwargs& kwargs)
{
  if(!progress.is_none() && !PyCallable_Check(progress.ptr()))
    raise(PyExc_TypeError, "progress: expected a callable (stage, value) or None");
  const Options o = read_options(f, kwargs);
  Mesh mesh = mesh_from_arrays(points, hexes);
  Surface surface;
  const bool has_reference = reference_surface(reference, surface);

  std::atomic<bool> stop(false);
  Python_visitor visitor;
  visitor.progress = progress;
  visitor.stop = &stop;
  namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
  namespace INP = CGAL::hex_mesh_internal_np;
  const auto public_np = CGAL::parameters::sharp_angle(o.sharp_angle)
                           .reference_feature_angle(o.reference_feature_angle)
                           .target_msj(o.target_msj)
                           .surface_tolerance(o.surface_tolerance)
                           .local_surface_tolerance(o.local_surface_tolerance)
                           .method(o.method)
                           .stop_flag(&stop)
                           .maximum_running_time(o.time_limit) // CGAL's, after the package's (parameters.h)
                           .number_of_iterations(o.number_of_iterations)
                           .visitor(std::ref(visitor));
  // the schedule's settings the binding exposes (not public C++ API)
  const auto np1 = HMOI::add_internal_parameter(public_np, INP::crease_seed_angle, o.crease_seed_angle);
  const auto np2 = HMOI::add_internal_parameter(np1, INP::turn_focus_band, o.turn_focus_band);
  const auto np3 = HMOI::add_internal_parameter(np2, INP::alpha, o.alpha);
  const auto np4 = HMOI::add_internal_parameter(np3, INP::beta, o.beta);
  const auto np5 = HMOI::add_internal_parameter(np4, INP::xi, o.xi);
  const auto np6 = HMOI::add_internal_parameter(np5, INP::relax_surface, o.relax_surface);
  const auto np7 = HMOI::add_internal_parameter(np6, INP::local_iterations, o.local_iterations);
  const auto np8 = HMOI::add_internal_parameter(np7, INP::barrier_fallback, o.barrier_fallback);
  const auto np9 = HMOI::add_internal_parameter(np8, INP::pull_back, o.pull_back);
  const auto np10 = HMOI::add_internal_parameter(np9, INP::asj_smoothing, o.asj_smoothing);
  const auto np11 = HMOI::add_internal_parameter(np10, INP::edge_angle_stages, o.edge_angle_stages);
  const auto np = HMOI::add_internal_parameter(np11, INP::coarse_level_start, o.coarse_level_start);
  HMO::Optimization_result r;
  {
    py::gil_scoped_release no_gil;
#ifdef CGAL_LINKED_WITH_TBB
    std::unique_ptr<tbb::global_control> threads;
    if(o.threads > 0)
      threads.reset(new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(o.threads)));
#endif
    try
    {
      r = has_reference ? call(f, mesh, HMOI::add_internal_parameter(np, INP::reference_surface, surface)) : call(f, mesh, np);
    }
    catch(const HMO::Reference_mismatch& e)
    {
      py::gil_scoped_acquire gil;
      raise(PyExc_ValueError, std::string("reference surface: ") + e.what());
    }
  }
  if(visitor.error) throw *visitor.error; // KeyboardInterrupt, or the progress callable's exception
  return py::make_tuple(points_array(mesh), result_dict(r));
}

} // namespace

PYBIND11_MODULE(_hexmesh_optimization, m)
{
  m.doc() = "Untangling and quality improvement of hexahedral meshes (CGAL package Hexahedral_mesh_optimization)";

  m.def("read", &read_mesh, py::arg("path"),
        "read(path) -> (points, hexes)\n\n"
        "Reads a hexahedral mesh, the format from the extension: .mesh, .vtk, .vtu, .msh, .inp, .exo, .e.\n"
        "points: float64 array (N, 3); hexes: int64 array (M, 8), MEDIT/VTK vertex order,\n"
        "numbered from 0. Raises OSError when the file cannot be opened, ValueError when it cannot be read.");
  m.def("write", &write_mesh, py::arg("path"), py::arg("points"), py::arg("hexes"), py::arg("cell_data") = py::none(),
        py::arg("format") = py::none(),
        "write(path, points, hexes, cell_data=None, format=None)\n\n"
        "Writes a hexahedral mesh, the format from the extension (.mesh, .vtk, .vtu, .msh, .inp, .exo, .e) or\n"
        "from format: 'mesh', 'vtk', 'vtk-binary', 'vtu', 'msh' (= 'msh41'), 'msh41', 'msh41-binary', 'msh22',\n"
        "'msh22-binary', 'inp', 'exo'. cell_data: a dict name -> one number per hexahedron, written as cell\n"
        "fields where the format has them (VTK, VTU, gmsh). The file is replaced atomically: on failure\n"
        "nothing is written. ValueError for a bad mesh, extension or format, OSError otherwise.");
  // for python -m hexmesh_optimization (__main__.py); not public
  py::class_<Mesh_file>(m, "_MeshFile")
    .def_static("read", &read_mesh_file, py::arg("path"))
    .def_property_readonly("points", [](const Mesh_file& f) { return points_array(f.mesh); })
    .def_property_readonly("hexes", [](const Mesh_file& f) { return hexes_array(f.mesh); })
    .def_readonly("warnings", &Mesh_file::warnings)
    .def("check_output", &check_mesh_file_output, py::arg("path"), py::arg("format") = py::none())
    .def("write", &write_mesh_file, py::arg("path"), py::arg("points"), py::arg("cell_data") = py::none(),
         py::arg("format") = py::none());
  m.def("_check_output_file", &check_output_file, py::arg("path"));
  m.def("scaled_jacobian", &scaled_jacobian, py::arg("points"), py::arg("hexes"),
        "scaled_jacobian(points, hexes) -> float64 array, the Verdict scaled Jacobian of each hexahedron\n"
        "(minimum over its 8 corners and its centre; negative: inverted).");
  m.def("quality", &quality, py::arg("points"), py::arg("hexes"),
        "quality(points, hexes) -> dict: hexes, vertices, inverted (scaled Jacobian < 0), msj, asj,\n"
        "histogram (20 counts), histogram_edges (21 bin edges from -1 to 1), certified_valid (hexahedra\n"
        "with a positive Jacobian at the 9 samples, decided exactly) and not_certified (their indices).");
  const char* options_doc =
    "Keyword options (the named parameters of the C++ functions, same names and defaults): sharp_angle,\n"
    "reference_feature_angle, alpha, beta, xi, relax_surface, local_iterations, number_of_iterations,\n"
    "barrier_fallback, "
    "surface_tolerance, local_surface_tolerance (a fraction of the shortest edge at each boundary vertex;\n"
    "None: none), method ('package' or 'paper'), time_limit (seconds, a hard stop, CGAL's\n"
    "maximum_running_time in C++; None: none),\n"
    "threads (0: every core; the result does not depend on it)";
  const std::string quality_options = std::string(options_doc) +
    ", and target_msj, pull_back, asj_smoothing, edge_angle_stages, coarse_level_start, crease_seed_angle,\n"
    "turn_focus_band.\n";
  const std::string common =
    "reference: None (the input boundary), a path to a surface (OBJ, OFF, STL, PLY) or a pair\n"
    "(vertices (N, 3), faces (F, 3 or 4)). progress: None or a callable (stage, value), called with the\n"
    "number of elements to fix when a stage starts and after its rounds, and 1.0 when it is done.\n"
    "Ctrl-C, or an exception raised by progress, stops the stages at their next safe point and is raised.\n"
    "Returns (new_points, report): report is a dict of everything Optimization_result holds (success,\n"
    "inverted/msj/asj before and after, surface_error, seconds, time_limit_reached, interrupted,\n"
    "warnings, unresolved, off_surface (boundary vertices beyond the tolerances: vertex, distance, allowed,\n"
    "local_length), certificate, stages). The GIL is released while optimising.\n";
  m.def("untangle",
        [](const py::array& p, const py::array& h, const py::object& ref, const py::object& progress,
           const py::kwargs& kw) { return run(Function::untangle, p, h, ref, progress, kw); },
        py::arg("points"), py::arg("hexes"), py::arg("reference") = py::none(), py::arg("progress") = py::none(),
        ("untangle(points, hexes, reference=None, progress=None, **options) -> (new_points, report)\n\n"
         "Removes the inverted elements (CGAL::untangle_hex_mesh). " + common + std::string(options_doc) + ".")
          .c_str());
  m.def("improve_quality",
        [](const py::array& p, const py::array& h, const py::object& ref, const py::object& progress,
           const py::kwargs& kw) { return run(Function::improve_quality, p, h, ref, progress, kw); },
        py::arg("points"), py::arg("hexes"), py::arg("reference") = py::none(), py::arg("progress") = py::none(),
        ("improve_quality(points, hexes, reference=None, progress=None, **options) -> (new_points, report)\n\n"
         "Raises the minimum scaled Jacobian of a valid mesh (CGAL::improve_hex_mesh_quality). " + common +
         quality_options).c_str());
  m.def("optimize",
        [](const py::array& p, const py::array& h, const py::object& ref, const py::object& progress,
           const py::kwargs& kw) { return run(Function::optimize, p, h, ref, progress, kw); },
        py::arg("points"), py::arg("hexes"), py::arg("reference") = py::none(), py::arg("progress") = py::none(),
        ("optimize(points, hexes, reference=None, progress=None, **options) -> (new_points, report)\n\n"
         "Untangles, then raises the minimum scaled Jacobian (CGAL::optimize_hex_mesh). " + common +
         quality_options).c_str());
}
