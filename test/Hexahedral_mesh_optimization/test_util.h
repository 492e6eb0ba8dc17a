// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Checks that run in every build type (CGAL builds Release, where NDEBUG
// removes assert). A failed check prints where and what, and the program
// exits with status 1 at the end. The test programs' mains (HMO_TEST_MAIN).

#ifndef HMO_TEST_UTIL_H
#define HMO_TEST_UTIL_H

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <sys/stat.h>

namespace hmo_test {

/// whether this is the sanitizer build (HMO_SANITIZED, -DHMO_SANITIZE=ON),
/// where a run is some 20 times slower: the tests with many or large runs
/// then take a sample of them (the Release build runs them all)
#ifdef HMO_SANITIZED
constexpr bool sanitized = true;
#else
constexpr bool sanitized = false;
#endif

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

/// runs one case of a test program and prints its wall time (where a
/// test's time goes; no check depends on it). With the environment variable
/// HMO_TEST_CASE set, only the cases whose call starts with it run.
template <class F>
void timed_case(const char* what, F f)
{
  const char* only = std::getenv("HMO_TEST_CASE");
  if(only && std::string(what).rfind(only, 0) != 0) return;
  const auto start = std::chrono::steady_clock::now();
  f();
  std::cout << "  [" << what << ": "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s]" << std::endl;
}

/// The test programs share one executable (test_main.cpp, fewer CGAL
/// translation units to compile): each registers its main under its name,
/// and `hmo_tests NAME [ARGS]` runs it with argv[0] = NAME.
typedef int (*Test_main)(int argc, char** argv);

inline std::map<std::string, Test_main>& test_programs()
{
  static std::map<std::string, Test_main> programs;
  return programs;
}

struct Test_registration
{
  Test_registration(const char* name, Test_main main) { test_programs()[name] = main; }
};

} // namespace hmo_test

/// `HMO_TEST_MAIN(name) { ... }`: the main of the test program `name`
#define HMO_TEST_MAIN(name)                                                    \
  int name##_main(int argc, char** argv);                                      \
  static const hmo_test::Test_registration name##_registration(#name, &name##_main); \
  int name##_main([[maybe_unused]] int argc, [[maybe_unused]] char** argv)

/// `HMO_CASE(test_something(args))`: runs the case, timed (`timed_case`)
#define HMO_CASE(call) hmo_test::timed_case(#call, [&] { call; })

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
