// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The readers the fuzz targets exercise, and the function that reads one
// input with one of them (fuzz_readers.cpp).

#ifndef HMO_FUZZ_READERS_H
#define HMO_FUZZ_READERS_H

#include <cstddef>
#include <cstdint>

#define HMO_FUZZ_MEDIT 1
#define HMO_FUZZ_VTK 2
#define HMO_FUZZ_VTU 3
#define HMO_FUZZ_OBJ 4
#define HMO_FUZZ_OFF 5
#define HMO_FUZZ_MSH 6
#define HMO_FUZZ_INP 7

/// reads `data` as a file of the format of `reader` (one of the above)
int hmo_fuzz_read(int reader, const std::uint8_t* data, std::size_t size);

#endif // HMO_FUZZ_READERS_H
