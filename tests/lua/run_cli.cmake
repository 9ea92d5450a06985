# Runs ${INVASIM} ${ARGS} and checks: the exit status is exactly ${RC} (0 success, 1 a refused
# input or runtime error, 2 a bad command line; a sanitizer finding exits with another status,
# scripts/test_sanitize.sh); the combined stdout+stderr matches EXPECT and does not match REJECT (regexes, may be empty);
# NO_FILE (if not empty) does not exist afterwards (it is removed first).
if(NOT NO_FILE STREQUAL "")
  file(REMOVE_RECURSE ${NO_FILE})
endif()
execute_process(COMMAND ${INVASIM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
set(all "${out}${err}")
message("exit status ${rc}; output:\n${all}")
if(rc MATCHES "[A-Za-z]")  # e.g. "Segmentation fault": a crash is never an acceptable failure
  message(FATAL_ERROR "invasim crashed: ${rc}")
endif()
if(NOT rc STREQUAL "${RC}")
  message(FATAL_ERROR "expected exit status ${RC}, got ${rc}")
endif()
if(NOT EXPECT STREQUAL "" AND NOT all MATCHES "${EXPECT}")
  message(FATAL_ERROR "output does not match: ${EXPECT}")
endif()
if(NOT REJECT STREQUAL "" AND all MATCHES "${REJECT}")
  message(FATAL_ERROR "output matches what it must not: ${REJECT}")
endif()
if(NOT NO_FILE STREQUAL "" AND EXISTS ${NO_FILE})
  message(FATAL_ERROR "${NO_FILE} was created despite the error")
endif()
