# FindMUMPS: Debian's double-precision MUMPS 5.x, which ships no CMake package configuration of its own.
#
# - NODUS_MUMPS_PARALLEL false (the default): the sequential library of libmumps-seq-dev. It runs in one
#   process, with OpenMP threads and the system BLAS, and needs no MPI.
# - NODUS_MUMPS_PARALLEL true: the MPI library of libmumps-dev, the one PETSc's MUMPS interface calls. Both
#   export the same symbols (dmumps_c and 877 more), so one program can hold only one of them; a build with
#   PETSc takes this one and gives it MPI_COMM_SELF where nodus factorises in one process.
#
# Imported target: MUMPS::dmumps. Result variable: MUMPS_FOUND.
#
# Only dmumps_c.h is needed to call it (the same header for both). The fake mpi.h of the sequential build
# (include/mumps_seq) is left out of the include path on purpose, so that it can never shadow a real MPI's.

find_path(MUMPS_INCLUDE_DIR NAMES dmumps_c.h)

if(NODUS_MUMPS_PARALLEL)
  set(_nodus_mumps_components dmumps mumps_common pord)
else()
  set(_nodus_mumps_components dmumps_seq mumps_common_seq mpiseq_seq pord_seq)
endif()
set(_nodus_mumps_required_vars MUMPS_INCLUDE_DIR)
foreach(_c IN LISTS _nodus_mumps_components)
  find_library(MUMPS_${_c}_LIBRARY NAMES ${_c})
  list(APPEND _nodus_mumps_required_vars MUMPS_${_c}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS REQUIRED_VARS ${_nodus_mumps_required_vars})

if(MUMPS_FOUND AND NOT TARGET MUMPS::dmumps)
  set(_nodus_mumps_libraries)
  foreach(_c IN LISTS _nodus_mumps_components)
    list(APPEND _nodus_mumps_libraries "${MUMPS_${_c}_LIBRARY}")
  endforeach()
  add_library(MUMPS::dmumps INTERFACE IMPORTED)
  set_target_properties(MUMPS::dmumps PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_nodus_mumps_libraries}")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR)
