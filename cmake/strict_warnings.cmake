# The warning set every target of the project is built with.
set(SIXPHASE_STRICT_FLAGS
    -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wdouble-promotion
    -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-qual
    -Wvla -Werror)

function(sixphase_strict target)
  target_compile_options(${target} PRIVATE ${SIXPHASE_STRICT_FLAGS})
endfunction()
