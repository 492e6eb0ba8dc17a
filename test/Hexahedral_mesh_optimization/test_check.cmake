# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The checks of the CMake-script tests (include()d by them):
# check(<message> <condition>...), the condition as for if(); a failed
# check is printed and counted in `failures`, which the script tests at its
# end.

set(failures 0)
function(check message)
  if(${ARGN})
  else()
    message(SEND_ERROR "check failed: ${message}")
    math(EXPR n "${failures} + 1")
    set(failures ${n} PARENT_SCOPE)
  endif()
endfunction()
