# Writes the version header at build time (cmake -P, run by the target invasim_version on every
# build), so that a binary built after a commit names that commit, not the one of the last
# configure. The header is rewritten only when its content changes (configure_file), so an
# unchanged revision recompiles nothing. A tree with uncommitted changes gets "-dirty".
# Inputs: SOURCE_DIR, TEMPLATE, OUTPUT, PROJECT_VERSION, GIT_EXECUTABLE (may be empty).
set(INVASIM_GIT_REVISION "")
if(GIT_EXECUTABLE AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" rev-parse --short HEAD
                  WORKING_DIRECTORY "${SOURCE_DIR}"
                  OUTPUT_VARIABLE INVASIM_GIT_REVISION
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  execute_process(COMMAND "${GIT_EXECUTABLE}" status --porcelain --untracked-files=no
                  WORKING_DIRECTORY "${SOURCE_DIR}"
                  OUTPUT_VARIABLE changes
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(INVASIM_GIT_REVISION AND changes)
    string(APPEND INVASIM_GIT_REVISION "-dirty")
  endif()
endif()
configure_file("${TEMPLATE}" "${OUTPUT}" @ONLY)
