# Python with matplotlib for the plots (Debian's python3-matplotlib): the reproduce figures
# (sixphase-sim) and the capture plots (sixphase-link). Sets the cache variable
# SIXPHASE_PLOT_PYTHON (empty when none is found: the tools then say so).
set(SIXPHASE_PLOT_PYTHON "" CACHE FILEPATH "Python interpreter with matplotlib for the plots")
if(NOT SIXPHASE_PLOT_PYTHON)
  foreach(cand /usr/bin/python3 python3)
    find_program(_py NAMES ${cand} NO_CACHE)
    if(_py)
      execute_process(COMMAND ${_py} -c "import matplotlib" RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_QUIET)
      if(_rc EQUAL 0)
        set(SIXPHASE_PLOT_PYTHON ${_py} CACHE FILEPATH "" FORCE)
        break()
      endif()
    endif()
    unset(_py)
  endforeach()
endif()
