# SuiteSparse/CHOLMOD from Debian ships no CMake config: locate it and wrap it in an
# imported target, lifelong::cholmod.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(lifelong::cholmod INTERFACE IMPORTED)
set_target_properties(lifelong::cholmod PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY};${SUITESPARSE_CONFIG_LIBRARY}")
