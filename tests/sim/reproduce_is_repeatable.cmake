# `sixphase-sim reproduce` twice into two directories: report.md and summary.json must be
# byte-identical (the committed report changes only when the commit does; host timings go to
# timings.md, which is not committed). Arguments: -DSIM=<sixphase-sim> -DWORK=<scratch dir>
foreach(run a b)
  file(REMOVE_RECURSE "${WORK}/${run}")
  execute_process(COMMAND "${SIM}" reproduce --out "${WORK}/${run}" --jobs 2 --no-plots --quiet
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "reproduce run ${run} failed (${rc})")
  endif()
endforeach()
foreach(file report.md summary.json)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${WORK}/a/${file}" "${WORK}/b/${file}"
                  RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${file} differs between two reproduce runs of the same build")
  endif()
endforeach()
file(READ "${WORK}/a/.gitignore" ignored)
if(NOT ignored MATCHES "timings.md")
  message(FATAL_ERROR "timings.md is not kept out of git")
endif()
message(STATUS "report.md and summary.json identical over two reproduce runs")
