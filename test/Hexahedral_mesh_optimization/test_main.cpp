// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The executable of the C++ test programs: `hmo_tests NAME [ARGS]` runs the
// test program NAME (registered by HMO_TEST_MAIN in test_NAME.cpp) with
// argv[0] = NAME and ARGS; `hmo_tests` alone lists them. CTest runs each
// program as the test of its name (CMakeLists.txt).

#include "test_util.h"

#include <iostream>

int main(int argc, char** argv)
{
  const auto& programs = hmo_test::test_programs();
  const auto program = argc > 1 ? programs.find(argv[1]) : programs.end();
  if(program == programs.end())
  {
    std::cerr << "usage: " << argv[0] << " TEST [ARGS...], where TEST is one of:\n";
    for(const auto& p : programs) std::cerr << "  " << p.first << "\n";
    return 2;
  }
  return program->second(argc - 1, argv + 1);
}
