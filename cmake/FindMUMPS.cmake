# FindMUMPS: the sequential double-precision MUMPS of Debian's libmumps-seq-dev (5.x), which ships no CMake
# package configuration of its own. Its libraries run in one process, with OpenMP threads and the system BLAS.
#
# Imported target: MUMPS::dmumps_seq. Result variable: MUMPS_FOUND.
#
# Only dmumps_c.h is needed to call it. The fake mpi.h of the sequential build (include/mumps_seq) is left out
# of the include path on purpose, so that it can never shadow a real MPI's header.

find_path(MUMPS_INCLUDE_DIR NAMES dmumps_c.h)

set(_nodus_mumps_components dmumps_seq mumps_common_seq mpiseq_seq pord_seq)
set(_nodus_mumps_required_vars MUMPS_INCLUDE_DIR)
foreach(_c IN LISTS _nodus_mumps_components)
  find_library(MUMPS_${_c}_LIBRARY NAMES ${_c})
  list(APPEND _nodus_mumps_required_vars MUMPS_${_c}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS REQUIRED_VARS ${_nodus_mumps_required_vars})

if(MUMPS_FOUND AND NOT TARGET MUMPS::dmumps_seq)
  set(_nodus_mumps_libraries)
  foreach(_c IN LISTS _nodus_mumps_components)
    list(APPEND _nodus_mumps_libraries "${MUMPS_${_c}_LIBRARY}")
  endforeach()
  add_library(MUMPS::dmumps_seq INTERFACE IMPORTED)
  set_target_properties(MUMPS::dmumps_seq PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_nodus_mumps_libraries}")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR)
