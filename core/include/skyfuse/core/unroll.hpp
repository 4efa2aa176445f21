#pragma once
/// \file
/// SKYFUSE_UNROLL before a loop with compile-time bounds asks the compiler to unroll it fully.
/// The small fixed-size kernels (9 x 9 Cholesky, 3 x 3 blocks) are triangular loop nests: left
/// alone, GCC keeps the loop control, which costs more than their few multiply-adds.

#if (defined(__GNUC__) || defined(__clang__)) && !defined(SKYFUSE_NOUNROLL)
#define SKYFUSE_UNROLL _Pragma("GCC unroll 16")
#else
#define SKYFUSE_UNROLL
#endif
