# Prints one of the lists of cmake/sources.cmake, one entry per line, for shell scripts:
#   cmake -P tools/print_sources.cmake SIXPHASE_TARGET_C_SOURCES
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/sources.cmake)
set(name ${CMAKE_ARGV3})
if(NOT DEFINED ${name})
  message(FATAL_ERROR "print_sources: no list ${name} in cmake/sources.cmake")
endif()
foreach(entry ${${name}})
  execute_process(COMMAND ${CMAKE_COMMAND} -E echo ${entry})
endforeach()
