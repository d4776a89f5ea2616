# Fails when a module includes a header of a module it must not depend on: the module DAG of
# the top CMakeLists.txt, checked on the sources (every module can see the repository root,
# so the compiler alone would not catch, say, render including a slam header).
#   cmake -DSOURCE_DIR=<repo> -P cmake/CheckModuleIncludes.cmake
# Run by ctest as `module_includes`.
cmake_minimum_required(VERSION 3.22)  # script mode: IN_LIST and friends
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckModuleIncludes: pass -DSOURCE_DIR=<repository root>")
endif()
# module -> the project folders its sources may include from (itself included). slam's
# sub-libraries (slam/CMakeLists.txt) are modules of their own, named with a slash.
set(slam_graph slam/graph)
set(slam_backend ${slam_graph} slam/backend)
set(slam_grid ${slam_graph} slam/grid)
set(slam_matching ${slam_grid} slam/matching)
set(slam_sparsify ${slam_backend} slam/sparsify)
set(slam_loops ${slam_matching} slam/loops)
set(slam_all ${slam_backend} ${slam_loops} slam/sparsify slam/mapping)
set(allowed_sensor sensor)
set(allowed_types sensor types)
set(allowed_sim sensor types sim)
foreach(sub graph backend grid matching sparsify loops)
  set(allowed_slam/${sub} sensor types ${slam_${sub}})
endforeach()
set(allowed_slam/mapping sensor types ${slam_all})
set(allowed_io sensor types slam/graph io)
set(allowed_render sensor types render)
set(allowed_eval sensor types sim ${slam_all} io render eval)
set(allowed_apps sensor types sim ${slam_all} io render eval apps)
set(project_folders sensor types sim slam io render eval apps tests bench fuzz)
set(modules sensor types sim slam/graph slam/backend slam/grid slam/matching slam/sparsify
    slam/loops slam/mapping io render eval apps)
set(violations "")
foreach(module IN LISTS modules)
  file(GLOB sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${module}/*.cpp"
       "${SOURCE_DIR}/${module}/*.hpp")
  foreach(source IN LISTS sources)
    file(STRINGS "${SOURCE_DIR}/${source}" includes REGEX "^#include \"[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" folder "${line}")
      if(folder STREQUAL "slam")  # a sub-library: slam/<name>
        string(REGEX REPLACE "^#include \"(slam/[a-z_]+)/.*" "\\1" folder "${line}")
      endif()
      if((folder IN_LIST project_folders OR folder MATCHES "^slam/")
         AND NOT folder IN_LIST allowed_${module})
        list(APPEND violations "${source}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
# Every folder of slam is a module above: a new one must join the DAG.
file(GLOB slam_entries LIST_DIRECTORIES true RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/slam/*")
foreach(entry IN LISTS slam_entries)
  if(IS_DIRECTORY "${SOURCE_DIR}/${entry}" AND NOT entry IN_LIST modules)
    list(APPEND violations "${entry}: a folder of slam that is not a module of this check")
  elseif(entry MATCHES "\\.(cpp|hpp)$")
    list(APPEND violations "${entry}: a source outside slam's sub-libraries")
  endif()
endforeach()
if(violations)
  list(JOIN violations "\n  " report)
  message(FATAL_ERROR "Includes against the module DAG (see the top CMakeLists.txt):\n  ${report}")
endif()
message(STATUS "CheckModuleIncludes: every module includes only what the DAG allows")
