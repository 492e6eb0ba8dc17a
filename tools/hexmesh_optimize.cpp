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
// The optimisation is `run_stages()`.

#include "hexmesh_optimize_options.h"
#include "quality_report.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/hex_mesh_reference_check.h>
#include <CGAL/hex_mesh_surface_error.h>
#include <CGAL/improve_hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <csignal>
#include <limits>
#include <memory>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

using hexmesh_optimize::format_fixed;

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef CGAL::Indexed_hex_mesh<Kernel::Point_3> Mesh;
typedef CGAL::Surface_mesh<Kernel::Point_3> Surface;
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

/// Ctrl-C (SIGINT) and SIGTERM: the first one sets the library's stop flag
/// (the stages stop at their next safe point, the last checked state is
/// written and the status is 128 + the signal); the handler then reverts to
/// the default, so a second one ends the program at once (the output is
/// written atomically: the previous file stays intact).
std::atomic<bool> stop_requested(false);
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void on_stop_signal(int sig)
{
  stop_signal = sig;
  stop_requested.store(true);
}

void install_stop_handlers()
{
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

/// Whether standard output is a terminal that understands "\r" and the
/// clear-to-end-of-line sequence (not TERM=dumb): the progress then updates
/// one line in place; otherwise (a pipe, a file, a test capturing the output)
/// it prints plain lines.
bool stdout_is_terminal()
{
  if(!isatty(STDOUT_FILENO))
    return false;
  const char* term = std::getenv("TERM");
  return term == nullptr || std::strcmp(term, "dumb") != 0;
}

/// Progress of the stages, on `log`. Plain (not a terminal): one line when
/// a stage starts, one every 2 seconds at most during long stages, one when
/// it ends. On a terminal: the line of the stage running is rewritten in
/// place ("\r", clear to the end of the line) with its name, round, elements
/// left and the seconds elapsed, at most 10 times a second; the line of a
/// stage that ends stays, as in the plain output.
struct Progress_visitor : CGAL::Hexahedral_mesh_optimization::Default_optimization_visitor
{
  std::ostream* log = nullptr;
  bool in_place = false; ///< a terminal: rewrite the line of the running stage
  Clock::time_point start = Clock::now();
  Clock::time_point last_round = Clock::now();
  bool line_open = false; ///< an in-place line is on the screen, without its newline

  std::string elapsed() const { return "[" + format_fixed(seconds_since(start), 1) + " s] "; }
  /// starts a line: on a terminal, over the in-place line
  std::ostream& begin_line()
  {
    if(in_place)
      *log << "\r\033[K";
    line_open = false;
    return *log << "  " << elapsed();
  }
  void end_in_place_line()
  {
    *log << std::flush;
    line_open = true;
  }

  void stage_started(const std::string& name, std::size_t bad)
  {
    if(!log) return;
    begin_line() << name << ": started";
    if(bad > 0) *log << ", " << bad << " elements to fix";
    if(in_place)
      end_in_place_line();
    else
      *log << std::endl;
    last_round = Clock::now();
  }
  void round_finished(const std::string& stage, int round, std::size_t left)
  {
    // plain: long stages report at most every 2 seconds; in place: 10 times a second
    if(!log || seconds_since(last_round) < (in_place ? 0.1 : 2.)) return;
    last_round = Clock::now();
    begin_line() << stage << ": round " << round + 1 << ", " << left << " elements left";
    if(in_place)
      end_in_place_line();
    else
      *log << std::endl;
  }
  void stage_finished(const CGAL::Hexahedral_mesh_optimization::Stage_report& r)
  {
    if(!log) return;
    begin_line() << r.name << ": done in " << format_fixed(r.seconds, 2) << " s, inverted " << r.inverted_before
                 << " -> " << r.inverted_after << ", MSJ " << format_fixed(r.msj_after, 3);
    if(!r.details.empty()) *log << "\n      " << r.details;
    *log << std::endl;
  }
  /// ends an in-place line left open (a run stopped inside a stage)
  void finish()
  {
    if(log && line_open)
      *log << "\r\033[K" << std::flush;
    line_open = false;
  }
};

/// The optimisation pipeline, run when an OUTPUT is given: the whole
/// pipeline (`CGAL::optimize_hex_mesh`) or, with --untangle, the untangling
/// only. Changes the vertex positions of `mesh` (never its connectivity).
/// `time_limit`: the hard stop left to the optimisation (infinity: none).
CGAL::Hexahedral_mesh_optimization::Optimization_result
run_stages(Mesh& mesh, const hexmesh_optimize::Hexmesh_optimize_options& options, const Surface* reference,
           double time_limit, bool progress_in_place, std::ostream& log)
{
  namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
  namespace INP = CGAL::hex_mesh_internal_np;
  Progress_visitor visitor;
  if(!options.quiet) visitor.log = &log;
  visitor.in_place = progress_in_place;
  if(!options.quiet)
    log << "\n" << (options.untangle_only ? "untangling" : "optimising") << " (" << mesh.hexahedra.size()
        << " hexahedra)\n";
  const auto public_np = CGAL::parameters::sharp_angle(options.sharp_angle)
                           .reference_feature_angle(options.reference_feature_angle)
                           .stop_flag(&stop_requested)
                           .target_msj(options.target_msj)
                           .surface_tolerance(options.surface_tolerance)
                           .local_surface_tolerance(options.local_surface_tolerance)
                           .method(options.paper_method ? CGAL::Hexahedral_mesh_optimization::Method::paper
                                                        : CGAL::Hexahedral_mesh_optimization::Method::package)
                           .paper_recipe(options.paper_recipe)
                           .maximum_running_time(time_limit) // CGAL's, after the package's (parameters.h)
                           .visitor(std::ref(visitor));
  // the schedule's settings the tool's options expose (not public API)
  const auto np = HMOI::add_internal_parameter(
    HMOI::add_internal_parameter(
      HMOI::add_internal_parameter(
        HMOI::add_internal_parameter(
          HMOI::add_internal_parameter(
            HMOI::add_internal_parameter(public_np, INP::crease_seed_angle, options.crease_seed_angle),
            INP::turn_focus_band, options.turn_focus_band),
          INP::relax_surface, options.relax_surface),
        INP::asj_smoothing, options.asj_smoothing),
      INP::pull_back, options.pull_back),
    INP::coarse_level_start, options.coarse_level);
  CGAL::Hexahedral_mesh_optimization::Optimization_result r;
  if(reference)
  {
    const auto npr = HMOI::add_internal_parameter(np, INP::reference_surface, *reference);
    r = options.untangle_only ? CGAL::untangle_hex_mesh(mesh, npr) : CGAL::optimize_hex_mesh(mesh, npr);
  }
  else
    r = options.untangle_only ? CGAL::untangle_hex_mesh(mesh, np) : CGAL::optimize_hex_mesh(mesh, np);
  visitor.finish();
  if(!options.quiet)
  {
    log << "  result: inverted " << r.inverted_before << " -> " << r.inverted_after << ", MSJ "
        << format_fixed(r.msj_before, 3) << " -> " << format_fixed(r.msj_after, 3);
    if(!options.untangle_only && options.target_msj < 1.)
      log << (r.msj_after >= options.target_msj ? " (target reached)" : " (target not reached)");
    if(r.kept_input) log << "; nothing better found, the input is kept";
    log << "\n";
    if(r.time_limit_reached)
      log << "  time limit reached: the stages stopped early and the last checked state is written\n";
    if(r.interrupted)
      log << "  interrupted by " << signal_name(stop_signal)
          << ": the stages stopped early and the last checked state is written\n";
  }
  return r;
}

/// The warnings of a run on standard error, even with --quiet: the elements
/// a solver will refuse (the first 20; all are in the JSON report), and the
/// optimiser's warnings but `already_printed`.
void print_run_warnings(const CGAL::Hexahedral_mesh_optimization::Optimization_result& r,
                        const std::string& already_printed)
{
  const std::size_t shown = 20;
  for(std::size_t i = 0; i < r.unresolved.size() && i < shown; ++i)
    std::cerr << "warning: hexahedron " << r.unresolved[i].hex << " still inverted (scaled Jacobian "
              << r.unresolved[i].scaled_jacobian << "): " << r.unresolved[i].details << "\n";
  if(r.unresolved.size() > shown)
    std::cerr << "warning: " << r.unresolved.size() - shown
              << " more hexahedra still inverted (all are in the --report JSON)\n";
  for(const std::string& w : r.warnings)
    if(w != already_printed) std::cerr << "warning: " << w << "\n";
  for(std::size_t i = 0; i < r.off_surface.size() && i < shown; ++i)
    std::cerr << "warning: boundary vertex " << r.off_surface[i].vertex << " at " << r.off_surface[i].distance
              << " from the reference surface (" << r.off_surface[i].allowed << " allowed, shortest edge at it "
              << r.off_surface[i].local_length << ")\n";
  if(r.off_surface.size() > shown)
    std::cerr << "warning: " << r.off_surface.size() - shown
              << " more boundary vertices off the reference surface (all are in the --report JSON)\n";
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
  int exit_status = 0;
  install_stop_handlers();
  const Clock::time_point program_start = Clock::now();
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> threads;
  if(options.threads > 0)
    threads.reset(new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(options.threads)));
#endif

  try
  {
    // ------------------------------------------- the outputs, before any work
    // a file that cannot be written is found out now, not after the
    // optimisation: its folder, a file created there (the writers' own
    // temporary, removed at once), and for OUTPUT whether the build writes
    // its format; the groups are checked once the mesh is read
    CGAL::IO::Hex_mesh_io_error io_error;
    const bool has_output = !options.output.empty();
    if(has_output && !CGAL::IO::check_hex_mesh_output(options.output_format, options.output, &io_error))
      return fail(io_error.what());
    for(const std::string* report : {&options.report_json, &options.histogram_svg})
      if(!report->empty() && !check_text_file_writable(*report, error))
        return fail(error);

    // ---------------------------------------------------------- read
    const Clock::time_point read_start = Clock::now();
    Mesh mesh;
    std::vector<std::string> warnings;
    const bool read = CGAL::IO::read_hex_mesh(options.input, mesh, &io_error, &warnings);
    for(const std::string& w : warnings)
      std::cerr << "warning: " << w << std::endl;
    if(!read)
      return fail(io_error.what());

    // the groups of the mesh read in the format of OUTPUT: refused (ids an
    // Exodus II file cannot hold) or written otherwise (references that are
    // not Exodus block ids) before the work rather than after it
    if(has_output)
    {
      warnings.clear();
      const bool writable =
        CGAL::IO::check_hex_mesh_output(options.output_format, options.output, mesh, &io_error, &warnings);
      for(const std::string& w : warnings)
        std::cerr << "warning: " << options.output << ": " << w << std::endl;
      if(!writable)
        return fail(io_error.what());
    }

    Surface reference;
    std::string reference_warning; // printed once, when the reference is read
    const bool has_reference = !options.reference.empty();
    if(has_reference)
    {
      std::string why;
      if(!CGAL::IO::read_reference_surface(options.reference, reference, &why))
        return fail(why);
      // before anything else: a reference in another frame, or of another
      // object, is a bad argument (exit status 2, no output)
      const CGAL::Hexahedral_mesh_optimization::Reference_fit fit = CGAL::hex_mesh_reference_fit(
        mesh, reference, CGAL::parameters::surface_tolerance(options.surface_tolerance));
      if(fit.verdict == CGAL::Hexahedral_mesh_optimization::Reference_fit::mismatched)
      {
        std::cerr << program << ": error: reference surface '" << options.reference << "' and mesh '"
                  << options.input << "': " << fit.message << std::endl;
        return 2;
      }
      if(fit.verdict == CGAL::Hexahedral_mesh_optimization::Reference_fit::distant)
      {
        reference_warning = fit.message;
        std::cerr << "warning: reference surface '" << options.reference << "': " << fit.message << std::endl;
      }
    }

    Mesh_report before;
    before.file = options.input;
    before.quality = CGAL::hex_mesh_quality(mesh);
    before.certificate = CGAL::hex_mesh_validity_certificate(mesh);
    before.seconds = seconds_since(read_start);
    // --worst: of the output, or of the input in report-only mode
    if(options.worst > 0 && !has_output)
      before.worst = worst_elements(mesh, CGAL::hex_mesh_scaled_jacobians(mesh), options.worst);
    if(!options.quiet)
    {
      print_quality_report(out, "before", before);
      out << "  read + quality: " << format_fixed(before.seconds, 3) << " s\n" << std::flush;
    }

    // ---------------------------------------------------- optimise, write
    Mesh_report after;
    Mesh input_mesh_for_check;
    if(has_output)
    {
      if(options.check && !has_reference) input_mesh_for_check = mesh; // the reference volume of --check
      const Clock::time_point start = Clock::now();
      // the hard stop counts from the start of the program: what reading took is spent
      const double time_left = options.time_limit > 0.
                                 ? (std::max)(1e-9, options.time_limit - seconds_since(program_start))
                                 : std::numeric_limits<double>::infinity();
      const CGAL::Hexahedral_mesh_optimization::Optimization_result r =
        run_stages(mesh, options, has_reference ? &reference : nullptr, time_left, stdout_is_terminal(), out);
      after.seconds = seconds_since(start);
      const std::vector<double> sj = CGAL::hex_mesh_scaled_jacobians(mesh);
      after.file = options.output;
      after.quality = CGAL::hex_mesh_quality(mesh);
      after.certificate = r.certificate; // the certificate of the mesh returned, as written
      // Hausdorff distance between the output boundary and the reference
      // surface (default: the input's boundary), relative to the diagonal of
      // the reference's bounding box, as the optimiser measured it
      after.surface_error = r.surface_error;
      after.time_limit_reached = r.time_limit_reached;
      after.interrupted = r.interrupted || stop_requested.load();
      after.warnings = r.warnings;
      after.unresolved = r.unresolved;
      after.off_surface = r.off_surface;
      if(options.worst > 0)
        after.worst = worst_elements(mesh, sj, options.worst);
      print_run_warnings(r, reference_warning);

      CGAL::IO::Hex_mesh_fields fields;
      // the formats with a place for cell fields (the others ignore them)
      fields.cell_scalars.push_back({"scaled_jacobian", sj});
      if(!CGAL::IO::write_hex_mesh_as(options.output_format, options.output, mesh, fields, &io_error))
        return fail(io_error.what());
      if(!options.quiet)
      {
        out << "\n";
        print_quality_report(out, "after", after);
        out << "  optimisation: " << format_fixed(after.seconds, 3) << " s\n" << std::flush;
      }
    }

    // ------------------------------------------------------- check
    bool check_failed = false;
    if(options.check && has_output && !stop_requested.load())
    {
      const CGAL::Hexahedral_mesh_optimization::Reference_volume_report rep =
        has_reference ? CGAL::check_hex_mesh_against_reference(mesh, reference)
                      : CGAL::check_hex_mesh_against_reference(mesh, input_mesh_for_check);
      check_failed = !rep.passed();
      if(!options.quiet || check_failed)
        out << "\nreference-volume check (TetGen):\n" << rep.summary() << std::flush;
    }

    // ------------------------------------------------------- reports
    if(!options.report_json.empty() &&
       !write_text_file(options.report_json, json_report(before, has_output ? &after : nullptr), error))
      return fail(error);
    if(!options.histogram_svg.empty() &&
       !write_text_file(options.histogram_svg, histogram_svg(before, has_output ? &after : nullptr), error))
      return fail(error);
    // the status says whether the output can be used: elements still
    // inverted or not certified valid (4) first, then a failed --check (3),
    // then a run cut short by the time limit (5)
    if(stop_requested.load())
    {
      std::cerr << program << ": interrupted by " << signal_name(stop_signal)
                << (has_output ? "; the last checked state was written to '" + options.output + "'" : std::string())
                << std::endl;
      exit_status = 128 + (stop_signal != 0 ? int(stop_signal) : SIGINT);
    }
    else if(has_output && (after.quality.inverted > 0 || !after.certificate.all_valid()))
      exit_status = 4;
    else if(check_failed)
      exit_status = 3;
    else if(has_output && after.time_limit_reached)
      exit_status = 5;
  }
  catch(const std::exception& e)
  {
    return fail(e.what());
  }
  return exit_status;
}
