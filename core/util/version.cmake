# Writes OUT (disco_version.h) with DISCO_VERSION_STRING = "VERSION (git COMMIT[-dirty])",
# run at every build (core/CMakeLists.txt) so the commit is never stale; the file is
# rewritten only when the text changes, so an unchanged tree rebuilds nothing.
# Inputs: -DVERSION=... -DSOURCE_DIR=... -DOUT=...
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE failed ERROR_QUIET)
if(failed OR commit STREQUAL "")
  set(commit "unknown")
endif()
set(text "#define DISCO_VERSION_STRING \"${VERSION} (git ${commit})\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
