# Runs springlab-run and compares the memory its summary says it used (the maximum resident size)
# with the guard's estimate made before the run: the estimate must cover what was used (else the
# guard lets through runs that cannot fit) without more than half as much again (else it refuses
# runs that fit).
# cmake -DCOMMAND="springlab-run|arg|..." -P memory_estimate.cmake
string(REPLACE "|" ";" COMMAND "${COMMAND}")
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "exit code ${code}, expected 0:\n${out}${err}")
endif()
if(NOT out MATCHES "memory: ([0-9]+) MiB at most in use \\(resident\\), about ([0-9]+) MiB estimated")
  message(FATAL_ERROR "no memory line in the summary:\n${out}")
endif()
set(used ${CMAKE_MATCH_1})
set(estimated ${CMAKE_MATCH_2})
math(EXPR most "${used} * 3 / 2 + 8")
if(estimated LESS used OR estimated GREATER most)
  message(FATAL_ERROR "estimated ${estimated} MiB for a run that used ${used} MiB: the estimate "
                      "should lie between ${used} and ${most} MiB\n${out}")
endif()
message(STATUS "used ${used} MiB, estimated ${estimated} MiB")
