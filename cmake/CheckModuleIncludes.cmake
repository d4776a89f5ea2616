# Fails when a module includes a header of a module it must not depend on: the module DAG of
# the top CMakeLists.txt, checked on the sources (every module can see the repository root,
# so the compiler alone would not catch, say, render including a slam header).
#   cmake -DSOURCE_DIR=<repo> -P cmake/CheckModuleIncludes.cmake
# Run by ctest as `module_includes`.
cmake_minimum_required(VERSION 3.22)  # script mode: IN_LIST and friends
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckModuleIncludes: pass -DSOURCE_DIR=<repository root>")
endif()
# module -> the project folders its sources may include from (itself included).
set(allowed_sensor sensor)
set(allowed_types sensor types)
set(allowed_sim sensor types sim)
set(allowed_slam sensor types slam)
set(allowed_io sensor types slam io)
set(allowed_render sensor types render)
set(allowed_eval sensor types sim slam io render eval)
set(allowed_apps sensor types sim slam io render eval apps)
set(project_folders sensor types sim slam io render eval apps tests bench fuzz)
set(violations "")
foreach(module sensor types sim slam io render eval apps)
  file(GLOB sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${module}/*.cpp"
       "${SOURCE_DIR}/${module}/*.hpp")
  foreach(source IN LISTS sources)
    file(STRINGS "${SOURCE_DIR}/${source}" includes REGEX "^#include \"[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" folder "${line}")
      if(folder IN_LIST project_folders AND NOT folder IN_LIST allowed_${module})
        list(APPEND violations "${source}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(violations)
  list(JOIN violations "\n  " report)
  message(FATAL_ERROR "Includes against the module DAG (see the top CMakeLists.txt):\n  ${report}")
endif()
message(STATUS "CheckModuleIncludes: every module includes only what the DAG allows")
