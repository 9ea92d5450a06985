# Runs ${INVASIM} ${ARGS} and checks the exit status is exactly ${RC} (2 for a bad command
# line, 1 for a runtime error), that stdout+stderr matches the regex ${EXPECT}, and, if
# ${NO_FILE} is given, that no such file exists afterwards (nothing written on an error).
if(DEFINED NO_FILE)
  file(REMOVE ${NO_FILE})
endif()
execute_process(COMMAND ${INVASIM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
set(all "${out}${err}")
message("exit status ${rc}; output:\n${all}")
if(NOT rc STREQUAL "${RC}")
  message(FATAL_ERROR "expected exit status ${RC}")
endif()
if(NOT all MATCHES "${EXPECT}")
  message(FATAL_ERROR "output does not match: ${EXPECT}")
endif()
if(DEFINED NO_FILE AND EXISTS ${NO_FILE})
  message(FATAL_ERROR "${NO_FILE} was written despite the error")
endif()
