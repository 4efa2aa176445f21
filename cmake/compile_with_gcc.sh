#!/usr/bin/env bash
# Runs a compile command of the clang build with GCC in place of clang++, for what clang 14 does
# not build as the project needs: Debian's libtorch 1.13 (its ATen/core/List.h destroys a vector
# of an incomplete type in C++20, which clang before 16 instantiates), so tools/train; and paper
# 001's LSTM kernels, whose AVX2 clones clang refuses (papers/CMakeLists.txt).
# Arguments: the launchers CMake was given (ccache), then the compiler and its arguments.
# GCC's objects link with clang's: both use Debian's libstdc++.
args=("$@")
for i in "${!args[@]}"; do
  case "${args[$i]}" in
    *clang++*) args[i]=g++; break ;;
  esac
done
exec "${args[@]}"
