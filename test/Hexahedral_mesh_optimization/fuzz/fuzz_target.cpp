// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One libFuzzer target: the reader HMO_FUZZ_READER (set by CMakeLists.txt)
// on every input (fuzz_readers.cpp).

#include "fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return hmo_fuzz_read(HMO_FUZZ_READER, data, size);
}
