#!/usr/bin/env bash
# Runs a compile command of the clang build with GCC in place of clang++: Debian's libtorch 1.13
# does not compile under clang 14 in C++20 (its ATen/core/List.h destroys a vector of an
# incomplete type, which clang before 16 instantiates), so tools/train compiles with GCC.
# Arguments: the launchers CMake was given (ccache), then the compiler and its arguments.
# GCC's objects link with clang's: both use Debian's libstdc++.
args=("$@")
for i in "${!args[@]}"; do
  case "${args[$i]}" in
    *clang++*) args[i]=g++; break ;;
  esac
done
exec "${args[@]}"
