# sixphase_prefix_symbols(<new_target> <prefix> <static_lib_target>...)
#
# Merges static libraries into one archive whose every defined global symbol carries
# <prefix>. The fixed and float builds of the control core define the same names; a host
# program that runs both in one process (fixed-vs-float tests, the simulator's --arith)
# links one of them through this renamed copy. References to symbols the libraries do not
# define themselves (libc, libm, the HAL) are left alone.
set(SIXPHASE_PREFIX_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/prefix_symbols_run.cmake)

function(sixphase_prefix_symbols new_target prefix)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/lib${new_target}.a)
  set(files)
  foreach(t ${ARGN})
    list(APPEND files $<TARGET_FILE:${t}>)
  endforeach()
  string(JOIN "|" joined ${files})
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DPREFIX=${prefix} -DLIBS=${joined}
            -DCC=${CMAKE_C_COMPILER} -DNM=${CMAKE_NM} -DOBJCOPY=${CMAKE_OBJCOPY}
            -DAR=${CMAKE_AR} -P ${SIXPHASE_PREFIX_SCRIPT}
    DEPENDS ${ARGN} ${SIXPHASE_PREFIX_SCRIPT}
    COMMENT "Prefixing symbols of ${ARGN} with ${prefix}"
    VERBATIM)
  add_custom_target(${new_target}_archive DEPENDS ${out})
  add_library(${new_target} STATIC IMPORTED GLOBAL)
  set_target_properties(${new_target} PROPERTIES IMPORTED_LOCATION ${out})
  add_dependencies(${new_target} ${new_target}_archive)
endfunction()
