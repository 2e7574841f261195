# Installs the built project into a scratch prefix, then configures, builds and runs the consumer,
# and checks that the consumer's compile command carries none of the project's own flags.
# -DBUILD_DIR=... -DSRC_DIR=... -DWORK=...
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK}/prefix" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SRC_DIR}" -B "${WORK}/build" -DCMAKE_BUILD_TYPE=Release
                        "-DCMAKE_PREFIX_PATH=${WORK}/prefix" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed")
endif()

# The project's warning and floating-point flags (cmake/Warnings.cmake) stay with the project;
# CGAL's compile flags stay inside the library's CGAL fence.
file(READ "${WORK}/build/compile_commands.json" commands)
if(NOT commands MATCHES "main\\.cpp" OR NOT commands MATCHES "-Werror")
  message(FATAL_ERROR "compile_commands.json lacks the consumer's own command:\n${commands}")
endif()
foreach(flag -Wshadow -Wconversion -Wpedantic -Wno-sign-conversion -ffp-contract=off -frounding-math)
  string(FIND "${commands}" "${flag}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the installed package imposes ${flag} on its consumer:\n${commands}")
  endif()
endforeach()

execute_process(COMMAND "${WORK}/build/consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "${out}")
if(rc)
  message(FATAL_ERROR "consumer returned ${rc}: ${out}")
endif()
