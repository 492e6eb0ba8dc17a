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

// The licence header of the Hexahedral Mesh Optimization package, included
// first by each of its headers, as CGAL's packages include theirs. The
// package is available under the GPL (v3 or later) only: there is no
// commercial licence of it, hence no CGAL_..._COMMERCIAL_LICENSE macro.
// With CGAL_LICENSE_WARNING defined a note says so; with CGAL_LICENSE_ERROR
// defined (which CGAL uses to refuse code used under the GPL) the
// compilation stops.
// The optional reference-volume check (CGAL::check_hex_mesh_against_reference(),
// when the package is configured with TetGen) links TetGen, which is under
// the AGPL (v3 or later): a program that uses it is bound by the AGPL too.

#ifndef CGAL_LICENSE_HEXAHEDRAL_MESH_OPTIMIZATION_H
#define CGAL_LICENSE_HEXAHEDRAL_MESH_OPTIMIZATION_H

#include <CGAL/config.h>
#include <CGAL/license.h>

#if defined(CGAL_LICENSE_WARNING)
  CGAL_pragma_warning("\nYou use the CGAL Hexahedral Mesh Optimization package under "
                      "the terms of the GPLv3+ (it has no commercial licence).")
#endif // CGAL_LICENSE_WARNING

#ifdef CGAL_LICENSE_ERROR
#  error "You use the CGAL Hexahedral Mesh Optimization package under the terms of \
          the GPLv3+ (it has no commercial licence). You get this error, as you \
          defined CGAL_LICENSE_ERROR."
#endif // CGAL_LICENSE_ERROR

#endif // CGAL_LICENSE_HEXAHEDRAL_MESH_OPTIMIZATION_H
