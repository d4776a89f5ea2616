# Fails when a module includes a header of a module it must not depend on: the module DAG of
# the top CMakeLists.txt, checked on the sources (every module can see the repository root,
# so the compiler alone would not catch, say, render including a slam header).
#   cmake -DSOURCE_DIR=<repo> -P cmake/CheckModuleIncludes.cmake
# Run by ctest as `module_includes`.
cmake_minimum_required(VERSION 3.22)  # script mode: IN_LIST and friends
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckModuleIncludes: pass -DSOURCE_DIR=<repository root>")
endif()
# module -> the project folders its sources may include from (itself included). The
# sub-libraries of slam and eval (their CMakeLists.txt) are modules of their own, named with
# a slash.
set(slam_graph slam/graph)
set(slam_backend ${slam_graph} slam/backend)
set(slam_grid ${slam_graph} slam/grid)
set(slam_removal ${slam_grid} slam/removal)
set(slam_matching ${slam_grid} slam/matching)
set(slam_sparsify ${slam_backend} slam/sparsify)
set(slam_loops ${slam_matching} slam/loops)
set(slam_all ${slam_backend} ${slam_loops} slam/sparsify slam/removal slam/mapping)
set(allowed_sensor sensor)
set(allowed_types sensor types)
set(allowed_sim sensor types sim)
foreach(sub graph backend grid removal matching sparsify loops)
  set(allowed_slam/${sub} sensor types ${slam_${sub}})
endforeach()
set(allowed_slam/mapping sensor types ${slam_all})
set(allowed_io sensor types slam/graph io)
set(allowed_render sensor types render)
set(eval_common eval/common)
set(eval_metrics ${eval_common} eval/metrics)
set(eval_figures ${eval_metrics} eval/figures)
set(eval_report ${eval_figures} eval/report)
set(eval_experiment ${eval_report} eval/experiment)
set(eval_sweep ${eval_experiment} eval/sweep)
set(eval_video ${eval_figures} eval/video)
set(eval_all ${eval_sweep} eval/video)
foreach(sub common metrics figures report experiment sweep video)
  set(allowed_eval/${sub} sensor types sim ${slam_all} io render ${eval_${sub}})
endforeach()
set(allowed_apps sensor types sim ${slam_all} io render ${eval_all} apps)
set(project_folders sensor types sim slam io render eval apps tests bench fuzz)
set(modules sensor types sim slam/graph slam/backend slam/grid slam/matching slam/sparsify
    slam/loops slam/removal slam/mapping io render eval/common eval/metrics eval/figures eval/report
    eval/experiment eval/sweep eval/video apps)
set(violations "")
foreach(module IN LISTS modules)
  file(GLOB sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${module}/*.cpp"
       "${SOURCE_DIR}/${module}/*.hpp")
  foreach(source IN LISTS sources)
    file(STRINGS "${SOURCE_DIR}/${source}" includes REGEX "^#include \"[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" folder "${line}")
      if(folder STREQUAL "slam" OR folder STREQUAL "eval")  # a sub-library: slam/<name>, eval/<name>
        string(REGEX REPLACE "^#include \"([a-z]+/[a-z_]+)/.*" "\\1" folder "${line}")
      endif()
      if((folder IN_LIST project_folders OR folder MATCHES "^(slam|eval)/")
         AND NOT folder IN_LIST allowed_${module})
        list(APPEND violations "${source}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
# Every folder of slam and eval is a module above: a new one must join the DAG.
file(GLOB split_entries LIST_DIRECTORIES true RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/slam/*"
     "${SOURCE_DIR}/eval/*")
foreach(entry IN LISTS split_entries)
  if(IS_DIRECTORY "${SOURCE_DIR}/${entry}" AND NOT entry IN_LIST modules)
    list(APPEND violations "${entry}: a folder that is not a module of this check")
  elseif(entry MATCHES "\\.(cpp|hpp)$")
    list(APPEND violations "${entry}: a source outside the sub-libraries")
  endif()
endforeach()
if(violations)
  list(JOIN violations "\n  " report)
  message(FATAL_ERROR "Includes against the module DAG (see the top CMakeLists.txt):\n  ${report}")
endif()
message(STATUS "CheckModuleIncludes: every module includes only what the DAG allows")
