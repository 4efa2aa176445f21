# skyfuse_compile_with_gcc(TARGET ...): in a clang build, the targets' files compile with GCC
# instead, after the launchers the build was given (ccache); in a GCC build, nothing. For what
# clang 14 does not build as the project needs: cmake/compile_with_gcc.sh says which and why.
function(skyfuse_compile_with_gcc)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    set_target_properties(${ARGN} PROPERTIES CXX_COMPILER_LAUNCHER
                          "${PROJECT_SOURCE_DIR}/cmake/compile_with_gcc.sh;${CMAKE_CXX_COMPILER_LAUNCHER}")
  endif()
endfunction()
