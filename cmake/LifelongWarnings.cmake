# Warnings on for every target of ours; -Werror is opt-in so that new compilers do not
# break a user's build, but CI turns it on.
option(LIFELONG_WERROR "Treat warnings as errors" OFF)
function(lifelong_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Woverloaded-virtual)
  if(LIFELONG_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# A sub-library of a module (slam/CMakeLists.txt, eval/CMakeLists.txt): the static library
# lifelong_<module>_<name>, aliased lifelong::<module>_<name>, with the project's warnings.
#   lifelong_sub_library(slam grid SOURCES a.cpp ... DEPS lifelong::slam_graph PRIVATE_DEPS ...)
function(lifelong_sub_library module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  set(target lifelong_${module}_${name})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(lifelong::${module}_${name} ALIAS ${target})
  target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  lifelong_warnings(${target})
endfunction()
