# Runs a command and checks its exit code, its output (stdout and stderr together) and,
# optionally, its number of output lines: a front end's behaviour as a user sees it.
# cmake -DCOMMAND="exe|arg|..." -DEXIT=2 [-DMATCH=regex] [-DLINES=n] -P run_and_check.cmake
string(REPLACE "|" ";" COMMAND "${COMMAND}")
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
if(NOT code STREQUAL "${EXIT}")
  message(FATAL_ERROR "exit code ${code}, expected ${EXIT}:\n${all}")
endif()
if(DEFINED MATCH AND NOT all MATCHES "${MATCH}")
  message(FATAL_ERROR "the output does not match '${MATCH}':\n${all}")
endif()
if(DEFINED LINES)
  string(REGEX MATCHALL "\n" newlines "${out}")
  list(LENGTH newlines count)
  if(NOT count EQUAL LINES)
    message(FATAL_ERROR "${count} lines on standard output, expected ${LINES}:\n${out}")
  endif()
endif()
