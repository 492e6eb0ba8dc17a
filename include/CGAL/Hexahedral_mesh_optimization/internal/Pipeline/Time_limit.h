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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_TIME_LIMIT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_TIME_LIMIT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The time limit of a run: a hard stop, and nothing else. No stage reads the
// clock to decide how much work to do (stages end on convergence or on work
// caps counted in sweeps, passes or iterations, see Optimization_schedule.h),
// so the same input and options give the same output whatever the machine's
// load. The only question a stage asks the clock is `reached()`, at its safe
// points (between vertices, regions, iterations); once it answers yes it
// answers yes for good, every stage then stops where it is, the drivers go
// back to the last state they checked, and the result says that the limit
// fired. Without a limit (the default) `reached()` never reads the clock.
//
// A stop flag (the `stop_flag` named parameter: Ctrl-C in the tool) is the
// same hard stop, set from outside: `reached()` answers yes once it is set,
// and `interrupted()` says that this, not the clock, fired.

#include <atomic>
#include <chrono>
#include <cmath>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

class Time_limit
{
  typedef std::chrono::steady_clock Clock;

public:
  /// no limit
  Time_limit() = default;
  /// `seconds` from now; a value that is not a positive finite number means no limit
  explicit Time_limit(double seconds) { reset(seconds); }

  Time_limit(const Time_limit&) = delete;
  Time_limit& operator=(const Time_limit&) = delete;

  void reset(double seconds)
  {
    m_limited = std::isfinite(seconds) && seconds > 0.;
    m_reached.store(false);
    m_interrupted.store(false);
    if(m_limited)
      m_deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  }

  bool is_limited() const { return m_limited; }

  /// also stop once `*flag` is true (null: no flag)
  void watch(const std::atomic<bool>* flag) { m_flag = flag; }

  /// whether the limit has passed or the stop flag is set (sticky; safe to
  /// call from several threads)
  bool reached() const
  {
    if(m_reached.load(std::memory_order_relaxed)) return true;
    if(m_flag != nullptr && m_flag->load(std::memory_order_relaxed))
    {
      m_interrupted.store(true, std::memory_order_relaxed);
      m_reached.store(true, std::memory_order_relaxed);
      return true;
    }
    if(!m_limited) return false;
    if(Clock::now() < m_deadline) return false;
    m_reached.store(true, std::memory_order_relaxed);
    return true;
  }

  /// whether `reached()` has answered yes (does not read the clock)
  bool fired() const { return m_reached.load(std::memory_order_relaxed); }
  /// whether it fired because of the stop flag
  bool interrupted() const { return m_interrupted.load(std::memory_order_relaxed); }
  /// whether it fired because of the clock
  bool limit_passed() const { return fired() && !interrupted(); }

private:
  bool m_limited = false;
  const std::atomic<bool>* m_flag = nullptr;
  mutable std::atomic<bool> m_interrupted{false};
  Clock::time_point m_deadline;
  mutable std::atomic<bool> m_reached{false};
};

/// `limit->reached()`, false for a null limit
inline bool time_limit_reached(const Time_limit* limit) { return limit != nullptr && limit->reached(); }

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_TIME_LIMIT_H
