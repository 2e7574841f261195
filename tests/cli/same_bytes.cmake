# Runs one CLI command twice, the second time with the environment variable ENV set to 1, and
# checks that both runs succeed and write the same bytes to FILE: a process-wide speed policy that
# the variable turns off must not change a result. Usage:
#   cmake -DCMD="a|b|c" -DENV=NAME -DFILE=path -P same_bytes.cmake
string(REPLACE "|" ";" CMD "${CMD}")
unset(ENV{${ENV}})
foreach(run on off)
  file(REMOVE "${FILE}")
  if(run STREQUAL "off")
    set(ENV{${ENV}} 1)
  endif()
  execute_process(COMMAND ${CMD} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${FILE}")
    message(FATAL_ERROR "run with ${ENV} ${run}: exit code ${rc}\ncommand: ${CMD}\nstderr: ${err}")
  endif()
  file(READ "${FILE}" bytes_${run} HEX)
endforeach()
if(NOT bytes_on STREQUAL bytes_off)
  message(FATAL_ERROR "${FILE} differs with ${ENV}=1: ${CMD}")
endif()
