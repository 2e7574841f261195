# Runs every command of the README's "Command line" block (```sh ... ```) and checks exit code 0,
# so that docs and behaviour agree. The file names of the README are bundled inputs copied into a
# fresh WORK directory; outputs are written there too. A README line with a new input name fails
# here ("cannot read") until the name is added to the table below.
# Usage: cmake -DCLI=path -DSRC=source_dir -DWORK=dir -P readme_commands.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(inputs
  "points.xy=tests/data/cli/square_point.xy"
  "points.dat=tests/data/cli/square_point.xy"
  "scan.xyz=examples/data/3d/tetra_interior.xyz"
  "scan.ply=tests/data/cli/tetra_interior_coloured.ply"
  "gt.off=tests/data/io/tetra_comments.off"
  "poly.idx=tests/data/cli/square_point_dent.idx"
  "gt.gt=tests/data/cli/square_point.gt"
  "table.csv=tests/data/cli/id_x_y_header.csv"
  "sites.geojson=tests/data/cli/square_point.geojson")
foreach(entry ${inputs})
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 name)
  list(GET pair 1 from)
  configure_file("${SRC}/${from}" "${WORK}/${name}" COPYONLY)
endforeach()

file(READ "${SRC}/README.md" readme)
string(FIND "${readme}" "## Command line" start)
if(start EQUAL -1)
  message(FATAL_ERROR "README.md has no '## Command line' section")
endif()
string(SUBSTRING "${readme}" ${start} -1 readme)
string(FIND "${readme}" "```sh\n" open)
string(SUBSTRING "${readme}" ${open} -1 readme)
string(LENGTH "```sh\n" skip)
string(SUBSTRING "${readme}" ${skip} -1 readme)
string(FIND "${readme}" "```" close)
string(SUBSTRING "${readme}" 0 ${close} block)

string(REPLACE ";" "\\;" block "${block}")
string(REPLACE "\n" ";" lines "${block}")
set(count 0)
foreach(line IN LISTS lines)
  string(REGEX REPLACE "#.*$" "" command "${line}")
  string(STRIP "${command}" command)
  if(command STREQUAL "")
    continue()
  endif()
  separate_arguments(args UNIX_COMMAND "${command}")
  list(GET args 0 program)
  if(NOT program STREQUAL "constrict")
    message(FATAL_ERROR "README command does not start with 'constrict': ${line}")
  endif()
  list(REMOVE_AT args 0)
  execute_process(COMMAND "${CLI}" ${args} WORKING_DIRECTORY "${WORK}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "README command failed (exit ${rc}): ${command}\nstdout: ${out}\nstderr: ${err}")
  endif()
  math(EXPR count "${count} + 1")
endforeach()
if(count LESS 10)
  message(FATAL_ERROR "only ${count} commands found in the README's Command line block")
endif()
message(STATUS "${count} README commands ran with exit code 0")
