# FindSuiteSparse: CHOLMOD, UMFPACK and KLU (with their AMD/COLAMD/METIS companions) from Debian's
# libsuitesparse-dev 5.x, which ships no CMake package configuration of its own.
#
# Imported targets: SuiteSparse::CHOLMOD, SuiteSparse::UMFPACK, SuiteSparse::KLU. Result variable: SuiteSparse_FOUND.

find_path(SuiteSparse_INCLUDE_DIR NAMES cholmod.h PATH_SUFFIXES suitesparse)

set(_nodus_ss_components cholmod umfpack klu btf amd colamd camd ccolamd suitesparseconfig metis)
set(_nodus_ss_required_vars SuiteSparse_INCLUDE_DIR)
foreach(_c IN LISTS _nodus_ss_components)
  find_library(SuiteSparse_${_c}_LIBRARY NAMES ${_c})
  list(APPEND _nodus_ss_required_vars SuiteSparse_${_c}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS ${_nodus_ss_required_vars})

if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  foreach(_c IN LISTS _nodus_ss_components)
    add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::${_c} PROPERTIES
      IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  endforeach()
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  target_link_libraries(SuiteSparse::CHOLMOD INTERFACE SuiteSparse::cholmod SuiteSparse::amd SuiteSparse::colamd
    SuiteSparse::camd SuiteSparse::ccolamd SuiteSparse::metis SuiteSparse::suitesparseconfig)
  add_library(SuiteSparse::UMFPACK INTERFACE IMPORTED)
  target_link_libraries(SuiteSparse::UMFPACK INTERFACE SuiteSparse::umfpack SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::KLU INTERFACE IMPORTED)
  target_link_libraries(SuiteSparse::KLU INTERFACE SuiteSparse::klu SuiteSparse::btf SuiteSparse::amd SuiteSparse::colamd
    SuiteSparse::suitesparseconfig)
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
