# ctest api_reference: runs doxygen on the installed headers (docs/Doxyfile.in) and fails, printing them, on any of
# its warnings (an undocumented public declaration, markup doxygen cannot read), or when doxygen itself fails.
#   cmake -DDOXYGEN=PATH -DDOXYFILE=PATH -DOUTPUT=DIR -P api_reference_check.cmake
foreach(var DOXYGEN DOXYFILE OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "api_reference_check.cmake: -D${var}= is required")
  endif()
endforeach()
file(MAKE_DIRECTORY ${OUTPUT})
set(log ${OUTPUT}/warnings.log)
file(REMOVE ${log})
execute_process(COMMAND ${DOXYGEN} ${DOXYFILE} WORKING_DIRECTORY ${OUTPUT} RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "doxygen ${DOXYFILE} exited ${status}:\n${out}")
endif()
if(NOT EXISTS ${log})
  message(FATAL_ERROR "doxygen wrote no warning log ${log}")
endif()
file(READ ${log} warnings)
if(NOT warnings STREQUAL "")
  string(REGEX MATCHALL ": warning: " each "${warnings}")
  list(LENGTH each n)
  message(NOTICE "${warnings}")  # as doxygen wrote them: FATAL_ERROR would re-wrap the lines
  message(FATAL_ERROR "doxygen: ${n} warnings (above; ${log}): document each declaration they name with a /// "
                      "comment, or quote the markup doxygen misreads")
endif()
message(STATUS "doxygen: no warnings; ${OUTPUT}/html/index.html")
