# Same seed -> byte-identical files, whatever the thread count; a different seed -> different
# bytes. For a one-target scenario (sweep.csv, sweep.json) and one with many aircraft
# (picture.csv, picture.json, and a picture that kept its guarantees: exit 0).
file(REMOVE_RECURSE "${WORK}")

# Runs `skyfuse ARGS` with --threads 1, --threads 2 and --seed 12345 into WORK/<tag>{a,b,c} and
# checks `files` there.
function(expect_same_seed_same_bytes tag files)
  set(args ${ARGN})
  execute_process(COMMAND ${SKYFUSE} ${args} --threads 1 --out ${WORK}/${tag}a RESULT_VARIABLE rc_a OUTPUT_QUIET)
  execute_process(COMMAND ${SKYFUSE} ${args} --threads 2 --out ${WORK}/${tag}b RESULT_VARIABLE rc_b OUTPUT_QUIET)
  execute_process(COMMAND ${SKYFUSE} ${args} --seed 12345 --out ${WORK}/${tag}c RESULT_VARIABLE rc_c OUTPUT_QUIET)
  if(NOT rc_a EQUAL 0 OR NOT rc_b EQUAL 0 OR NOT rc_c EQUAL 0)
    message(FATAL_ERROR "${args}: failed: ${rc_a} ${rc_b} ${rc_c}")
  endif()
  foreach(f ${files})
    file(SHA256 ${WORK}/${tag}a/${f} ha)
    file(SHA256 ${WORK}/${tag}b/${f} hb)
    file(SHA256 ${WORK}/${tag}c/${f} hc)
    if(NOT ha STREQUAL hb)
      message(FATAL_ERROR "${f}: same seed gave different bytes")
    endif()
    if(ha STREQUAL hc)
      message(FATAL_ERROR "${f}: a different seed gave the same bytes")
    endif()
  endforeach()
endfunction()

expect_same_seed_same_bytes("" "sweep.csv;sweep.json" sweep --runs 4 --steps 300 --max-stations 3 --no-plot)
file(STRINGS ${WORK}/a/sweep.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 7)  # header + 3 station counts x 2 speeds
  message(FATAL_ERROR "sweep.csv has ${n} lines, expected 7")
endif()
message(STATUS "same seed: identical bytes; other seed: different bytes")

expect_same_seed_same_bytes(p "picture.csv;picture.json"
  sweep --scenario ${SOURCE}/scenarios/uam-city.yaml --runs 4 --steps 60)
message(STATUS "picture: same seed identical bytes; other seed different bytes")
