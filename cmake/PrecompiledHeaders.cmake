# Precompiled headers: the node programs, the harness and the test binaries parse the project
# headers most of their files include once a target, not once a file. A median file of theirs
# spent a third to a half of its time parsing headers (clang's -ftime-trace), most of it the
# project's own templates; a target's precompiled header holds them and their Eigen and standard
# instantiations (-fpch-instantiate-templates, which CMake adds for clang).
# docs/testing.md#precompiled-headers has what it saves and what did not.
#
#   skyfuse_precompile_headers(TARGET HEADER...)
#
# HEADERs are written as an #include would (<vector>, <skyfuse/core/types.hpp>), and are other
# libraries' headers, never the target's own: CMake marks its precompiled header a system header,
# and clang then treats everything it includes as one and does not warn in it. Every header
# listed is also compiled, with warnings, by the files of a target without one (core has none:
# its heavy files gained nothing from one). A header must not depend on a macro a file defines
# before its includes: SKYFUSE_SHARD is defined by the shards' generated files and read only by
# the shard sources.
#
# On by default with clang, the build's compiler. Under GCC 12 they were measured not worth it
# (0.99 of the files' CPU, and two false -Warray-bounds that -Werror makes failures), so off.
# Off, every file parses what it includes itself: also the way to check that each file includes
# what it uses.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(pch_default ON)
else()
  set(pch_default OFF)
endif()
option(SKYFUSE_PRECOMPILED_HEADERS "Parse the largest targets' common headers once a target"
       ${pch_default})

# ccache can cache files compiled with a precompiled header only with these sloppinesses, and
# with clang's timestamp left out of the header (man ccache, "Precompiled headers").
if(SKYFUSE_PRECOMPILED_HEADERS AND CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
  set(CMAKE_CXX_COMPILER_LAUNCHER
      "${CMAKE_COMMAND};-E;env;CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime;${CMAKE_CXX_COMPILER_LAUNCHER}")
endif()

# The standard library as the project uses it: in nearly every file of every target below.
set(SKYFUSE_PCH_STD <algorithm> <array> <cmath> <cstddef> <cstdint> <functional> <map> <memory>
    <optional> <set> <span> <sstream> <stdexcept> <string> <string_view> <tuple> <type_traits>
    <utility> <variant> <vector>)

# What the node programs (skyfuse-station, skyfuse-center) include in most files: the filter
# parts' increments, the scenario and the wire.
set(SKYFUSE_PCH_NODE ${SKYFUSE_PCH_STD} <Eigen/Core> <Eigen/Cholesky> <fmt/format.h>
    <skyfuse/wire/skyfuse_picture.h> <skyfuse/core/small_cholesky.hpp> <skyfuse/core/status.hpp>
    <skyfuse/fusion/increment_fusion.hpp> <skyfuse/fusion/mixed_stacked_ekf.hpp>
    <skyfuse/registry/registry.hpp> <skyfuse/registry/make_parts.hpp>
    <skyfuse/scenario/scenario.hpp> <skyfuse/sim/run_plan.hpp>
    <skyfuse/tracking/ekf_increment_rule.hpp> <skyfuse/tracking/unscented_increment_rule.hpp>
    <skyfuse/tracking/network_imm.hpp> <skyfuse/tracking/step_collector.hpp>
    <skyfuse/validation/drop_kind.hpp> <skyfuse/validation/nis_gate.hpp>
    <skyfuse/options/node_options.hpp> <skyfuse/transport/dds_node.hpp>
    <skyfuse/transport/source_binding.hpp> <skyfuse/transport/wire_conversion.hpp>)

function(skyfuse_precompile_headers target)
  if(NOT SKYFUSE_PRECOMPILED_HEADERS)
    return()
  endif()
  target_precompile_headers(${target} PRIVATE ${ARGN})
  skyfuse_pch_without_timestamp(${target})
endfunction()

# skyfuse_reuse_precompiled_headers(TARGET OWNER): TARGET's files use OWNER's precompiled header,
# made once; both must be compiled with the same options and definitions.
function(skyfuse_reuse_precompiled_headers target owner)
  if(NOT SKYFUSE_PRECOMPILED_HEADERS)
    return()
  endif()
  target_precompile_headers(${target} REUSE_FROM ${owner})
  skyfuse_pch_without_timestamp(${target})
endfunction()

# clang writes the header's timestamp into it, which ccache cannot cache (above).
function(skyfuse_pch_without_timestamp target)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    target_compile_options(${target} PRIVATE "SHELL:-Xclang -fno-pch-timestamp")
  endif()
endfunction()
