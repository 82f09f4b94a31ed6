# FindPCG -- the PCG random number generators (pcg-cpp, header-only; Debian: libpcg-cpp-dev), which ship no CMake
# package of their own. Defines PCG_FOUND and the target PCG::PCG.
find_path(PCG_INCLUDE_DIR pcg_random.hpp)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(PCG REQUIRED_VARS PCG_INCLUDE_DIR)
if(PCG_FOUND AND NOT TARGET PCG::PCG)
  add_library(PCG::PCG INTERFACE IMPORTED)
  set_target_properties(PCG::PCG PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${PCG_INCLUDE_DIR}")
endif()
mark_as_advanced(PCG_INCLUDE_DIR)
