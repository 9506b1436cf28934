# Runs a Catch2 test executable and checks that it fails as a proof requires:
#   MODE=every  every test case fails, each with the "not implemented yet" message (the stubs)
#   MODE=some   at least one test case fails, and none crashes (a mutant)
# cmake -DEXE=path -DSPEC=[task1] -DMODE=every -P expect_failures.cmake
execute_process(COMMAND "${EXE}" "${SPEC}" RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE out)

if(NOT code MATCHES "^[0-9]+$")
  message(FATAL_ERROR "${EXE} ${SPEC} crashed (${code}) instead of reporting failures:\n${out}")
endif()
if(out MATCHES "All tests passed")
  message(FATAL_ERROR "${EXE} ${SPEC}: every test passed, but this code should fail them:\n${out}")
endif()
if(NOT out MATCHES "test cases: *([0-9]+) \\|")
  message(FATAL_ERROR "${EXE} ${SPEC}: no Catch2 summary in the output:\n${out}")
endif()
set(total ${CMAKE_MATCH_1})
string(REGEX MATCH "([0-9]+) failed" _ "${out}")
set(failed ${CMAKE_MATCH_1})

if(MODE STREQUAL "every")
  string(REGEX MATCHALL "is not implemented yet" messages "${out}")
  list(LENGTH messages reported)
  if(NOT failed EQUAL total OR reported LESS total)
    message(FATAL_ERROR "${EXE} ${SPEC}: ${failed} of ${total} test cases failed and ${reported} "
                        "said 'not implemented yet'; on the starter code every test must fail "
                        "with that message. (If you are a student who has started the tasks, "
                        "run ./lab test --student instead.)\n${out}")
  endif()
  message(STATUS "all ${total} test cases fail on the starter code, each naming what to write")
elseif(MODE STREQUAL "some")
  if(failed LESS 1)
    message(FATAL_ERROR "${EXE} ${SPEC}: no test failed:\n${out}")
  endif()
  message(STATUS "caught: ${failed} of ${total} test cases fail")
else()
  message(FATAL_ERROR "MODE must be every or some, not '${MODE}'")
endif()
