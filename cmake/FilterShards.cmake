# Code compiled for every registered filter part (a node process's rounds, the Monte Carlo's
# steppers) can be split over shards, one translation unit each, so that more cores compile them
# side by side and none takes minutes or gigabytes alone
# (core/include/skyfuse/registry/filter_shards.hpp says how the code is written).
#
#   skyfuse_filter_shards(TARGET SOURCE [SOURCE...] [BY_SENSOR])
#
# adds SOURCE to TARGET once per shard, through a generated file that defines SKYFUSE_SHARD and
# includes it, and gives TARGET the shard count as SKYFUSE_FILTER_SHARDS and the sensor parts'
# count as SKYFUSE_SENSOR_PARTS. With BY_SENSOR, once per shard and sensor part, the file
# defining SKYFUSE_SENSOR_PART too (registry/sensor_parts.hpp): for code that instantiates the
# peers and the center for every sensor. With several sources, each generated file includes them
# all, one translation unit per shard (and part) named after the first: for sources that
# instantiate much the same arithmetic of a group, which one file then instantiates once.

# How many shards, and which configuration groups (a filter part on one motion model it runs on,
# registry/configuration_groups.hpp: 10) each compiles. A shard compiles again the headers and
# its groups' shared code, not the DDS side of the node processes, which is compiled once per
# fusion with the sensors and filter arithmetic apart from it (stations/station_sensing.hpp,
# fusion_center/center_rounds.hpp). What a file costs is mostly its part and model, not its
# sensors, and groups on one motion model share much of it: so groups share a shard where that
# is cheaper and stays under 1.5 GB, and the rest have one each (SKYFUSE_SHARD_GROUPS, below).
# One file per program (1, which ./quickstart demo takes for a newcomer's first build) took
# 141 s and 4.3 GB for its largest file (docs/testing.md#the-largest-files). With a count other
# than SKYFUSE_SHARD_GROUPS's, shard s holds the groups whose number modulo the count is s. A
# group added to the registry beyond those listed joins a shard by the same rule; nothing here
# needs changing.
#
# The shards' groups: the EKF and the unscented filter on constant velocity (groups 1 and 8)
# in one, the three parts on paper 002's relative motion (2, 6, 9) in one, every other group
# alone. Compiled together, clang took 25.9 s for the one-aircraft rounds and Monte Carlo of
# groups 1 and 8 against 22.5 + 12.9 s apart, and 33.9 s for their pictures against
# 27.2 + 24.4 s (1.24 and 1.37 GB); the pictures of the EKF and the unscented filter on constant
# acceleration (0 and 7) took 41.2 s against 33.7 + 29.3 s but 1.70 GB, so they stay apart
# (docs/testing.md#the-largest-files).
set(SKYFUSE_SHARD_GROUPS "0;1 8;2 6 9;3;4;5;7" CACHE STRING
    "The configuration groups of each shard, a shard a list item, its groups space-separated")
list(LENGTH SKYFUSE_SHARD_GROUPS shard_groups_count)
set(SKYFUSE_FILTER_SHARDS ${shard_groups_count} CACHE STRING
    "Translation units per program for the code of every filter part (1: one file each)")
if(NOT SKYFUSE_FILTER_SHARDS MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "SKYFUSE_FILTER_SHARDS must be a whole number >= 1, got '${SKYFUSE_FILTER_SHARDS}'")
endif()

# The shard of each group, in the groups' order, for registry/filter_shards.hpp; none (each group
# by its number modulo the count) unless the count is SKYFUSE_SHARD_GROUPS's. The groups listed
# must be 0, 1, ... each once.
set(SKYFUSE_SHARD_OF_GROUP "")
set(shards_by_groups OFF)
if(SKYFUSE_FILTER_SHARDS EQUAL shard_groups_count)
  set(shards_by_groups ON)
  set(shard 0)
  set(groups_listed 0)
  foreach(groups IN LISTS SKYFUSE_SHARD_GROUPS)
    string(REPLACE " " ";" groups "${groups}")
    foreach(group IN LISTS groups)
      if(NOT group MATCHES "^[0-9]+$" OR DEFINED shard_of_group_${group})
        message(FATAL_ERROR "SKYFUSE_SHARD_GROUPS: '${group}' is not a group number, or in two shards")
      endif()
      set(shard_of_group_${group} ${shard})
      math(EXPR groups_listed "${groups_listed} + 1")
    endforeach()
    math(EXPR shard "${shard} + 1")
  endforeach()
  math(EXPR last_group "${groups_listed} - 1")
  foreach(group RANGE ${last_group})
    if(NOT DEFINED shard_of_group_${group})
      message(FATAL_ERROR "SKYFUSE_SHARD_GROUPS lists ${groups_listed} groups but not group ${group}")
    endif()
    # Each followed by a comma: the header's array ends with a mark of its own.
    string(APPEND SKYFUSE_SHARD_OF_GROUP "${shard_of_group_${group}}, ")
  endforeach()
endif()

# Sensor parts: the sources that instantiate the peers and the center for every sensor kind
# (the Monte Carlo's, the center's rounds and core's filter rounds) split each shard again by
# the stations' sensor. 2 keeps every file at most 1.39 GB (the largest five were 1.52-1.66 GB)
# but each half compiles again what the sensors share: those sources took 765 s of CPU instead
# of 508 s, 14 % more for the whole build, and a build with one file per program would pay the
# same in its largest files. So 1 by default, with the shards of SKYFUSE_SPLIT_SHARDS in 2 (109 s
# more CPU, not 257), and 2 or more for a machine whose memory is short of two 1.4 GB compilers
# (docs/testing.md#the-largest-files).
set(SKYFUSE_SENSOR_PARTS 1 CACHE STRING
    "Translation units per shard, by the stations' sensor, for the sources compiled for every sensor")
if(NOT SKYFUSE_SENSOR_PARTS MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "SKYFUSE_SENSOR_PARTS must be a whole number >= 1, got '${SKYFUSE_SENSOR_PARTS}'")
endif()

# The shards split in two sensor parts all the same, under GCC: those whose files were above
# 1.5 GB with one, the EKF on constant acceleration (shard 0: the center, 1.53 GB), on paper
# 002's relative motion (2: the center and the Monte Carlo, 1.56 and 1.52 GB) and the default IMM
# (3: the Monte Carlo and the picture, 1.62 and 1.66 GB). Splitting only these takes every file
# under 1.5 GB for a fraction of what splitting every shard costs. Clang, the build's compiler,
# compiles each of them whole in at most 1.09 GB, and in less CPU than its two halves (the
# filter rounds of shard 0, 20.0 s against 11.6 + 12.6 s; docs/testing.md#the-largest-files), so
# it splits none. Numbers are shards of SKYFUSE_SHARD_GROUPS (0 the EKF on constant
# acceleration, 2 the parts on relative motion, 3 the default IMM); with another
# SKYFUSE_FILTER_SHARDS the list is ignored.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(split_by_default "")
else()
  set(split_by_default "0;2;3")
endif()
set(SKYFUSE_SPLIT_SHARDS "${split_by_default}" CACHE STRING
    "Shards compiled in (at least) two sensor parts whatever SKYFUSE_SENSOR_PARTS says")

# The sensor parts of each shard, for the sources and, through a generated header, for the code
# that picks a shard's part (registry/sensor_parts.hpp).
function(skyfuse_sensor_parts_of shard out)
  set(parts ${SKYFUSE_SENSOR_PARTS})
  if(shards_by_groups AND shard IN_LIST SKYFUSE_SPLIT_SHARDS AND parts LESS 2)
    set(parts 2)
  endif()
  set(${out} ${parts} PARENT_SCOPE)
endfunction()
set(parts_by_shard "")
math(EXPR last_shard "${SKYFUSE_FILTER_SHARDS} - 1")
foreach(shard RANGE ${last_shard})
  skyfuse_sensor_parts_of(${shard} parts)
  list(APPEND parts_by_shard ${parts})
endforeach()
string(REPLACE ";" ", " SKYFUSE_SENSOR_PARTS_BY_SHARD "${parts_by_shard}")
# Both for the code, in one generated header: registry/filter_shards.hpp and sensor_parts.hpp.
file(CONFIGURE OUTPUT "${PROJECT_BINARY_DIR}/generated/skyfuse/registry/shard_layout.hpp"
     CONTENT "// Generated by cmake/FilterShards.cmake: the shard of each configuration group (none where a group's shard is its number modulo the count) and the sensor parts of each shard.\n#pragma once\n#define SKYFUSE_SHARD_OF_GROUP @SKYFUSE_SHARD_OF_GROUP@\n#define SKYFUSE_SENSOR_PARTS_BY_SHARD @SKYFUSE_SENSOR_PARTS_BY_SHARD@\n"
     @ONLY)

include("${CMAKE_CURRENT_LIST_DIR}/CompiledFilterParts.cmake")

function(skyfuse_filter_shards target source)
  cmake_parse_arguments(PARSE_ARGV 2 arg "BY_SENSOR" "" "")
  get_filename_component(stem "${source}" NAME_WE)
  set(includes "")
  foreach(each IN ITEMS ${source} ${arg_UNPARSED_ARGUMENTS})
    get_filename_component(each_path "${each}" ABSOLUTE)
    string(APPEND includes "#include \"${each_path}\"\n")
  endforeach()
  math(EXPR last "${SKYFUSE_FILTER_SHARDS} - 1")
  foreach(shard RANGE ${last})
    set(parts 1)
    if(arg_BY_SENSOR)
      skyfuse_sensor_parts_of(${shard} parts)
    endif()
    math(EXPR last_part "${parts} - 1")
    foreach(part RANGE ${last_part})
      if(parts EQUAL 1)
        set(generated "${CMAKE_CURRENT_BINARY_DIR}/${stem}_${shard}.cpp")
      else()
        set(generated "${CMAKE_CURRENT_BINARY_DIR}/${stem}_${shard}_${part}.cpp")
      endif()
      file(CONFIGURE OUTPUT "${generated}" CONTENT
           "// Generated by cmake/FilterShards.cmake: shard @shard@ of @SKYFUSE_FILTER_SHARDS@, sensor part @part@ of @parts@.\n#define SKYFUSE_SHARD @shard@\n#define SKYFUSE_SENSOR_PART @part@\n@includes@"
           @ONLY)
      target_sources(${target} PRIVATE "${generated}")
    endforeach()
  endforeach()
  target_compile_definitions(${target} PRIVATE SKYFUSE_FILTER_SHARDS=${SKYFUSE_FILTER_SHARDS}
                                                SKYFUSE_SENSOR_PARTS=${SKYFUSE_SENSOR_PARTS})
endfunction()
