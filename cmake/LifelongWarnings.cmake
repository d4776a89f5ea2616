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
