# Script mode: writes build_info.hpp only when its content changes (no needless rebuilds).
find_package(Git QUIET)
set(SHA "unknown")
set(DIRTY "false")
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SRC} rev-parse HEAD OUTPUT_VARIABLE SHA
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    set(SHA "unknown")
  endif()
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SRC} status --porcelain --untracked-files=no
                  OUTPUT_VARIABLE ST ERROR_QUIET)
  if(NOT "${ST}" STREQUAL "")
    set(DIRTY "true")
  endif()
endif()
configure_file(${IN} ${OUT}.tmp @ONLY)
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
