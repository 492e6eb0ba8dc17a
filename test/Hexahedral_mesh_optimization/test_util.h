// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Checks that run in every build type (CGAL builds Release, where NDEBUG
// removes assert). A failed check prints where and what, and the program
// exits with status 1 at the end.

#ifndef HMO_TEST_UTIL_H
#define HMO_TEST_UTIL_H

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <sys/stat.h>

namespace hmo_test {

inline int& failures() { static int n = 0; return n; }

inline int report(const char* program)
{
  if(failures() == 0)
    std::cout << program << ": all checks passed" << std::endl;
  else
    std::cout << program << ": " << failures() << " check(s) FAILED" << std::endl;
  return failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

inline bool file_exists(const std::string& path)
{
  struct stat s;
  return ::stat(path.c_str(), &s) == 0;
}

/// the shared data folder, or an empty string (with a message) when absent
inline std::string shared_data_dir()
{
  const std::string dir = HMO_SHARED_DATA_DIR;
  if(!file_exists(dir + "/README.md"))
  {
    std::cout << "shared data folder " << dir << " is absent: shared-mesh checks skipped" << std::endl;
    return std::string();
  }
  return dir;
}

} // namespace hmo_test

#define HMO_CHECK(cond)                                                        \
  do {                                                                         \
    if(!(cond)) {                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond     \
                << std::endl;                                                  \
      ++hmo_test::failures();                                                  \
    }                                                                          \
  } while(false)

#define HMO_CHECK_CLOSE(a, b, tol)                                             \
  do {                                                                         \
    const double hmo_a_ = (a), hmo_b_ = (b);                                   \
    if(!(std::abs(hmo_a_ - hmo_b_) <= (tol))) {                                \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #a        \
                << " = " << hmo_a_ << " vs " #b " = " << hmo_b_                \
                << " (tolerance " << (tol) << ")" << std::endl;                \
      ++hmo_test::failures();                                                  \
    }                                                                          \
  } while(false)

#endif // HMO_TEST_UTIL_H
