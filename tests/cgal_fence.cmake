# The CGAL fence (src/CMakeLists.txt): only src/cgal/ includes CGAL headers, so the rest of the
# library, the CLI, the tools, the bindings and the tests compile without CGAL. bench/ is left out
# on purpose: it times CGAL's own Delaunay as the reference.
# -DROOT=<source dir>
set(offenders "")
foreach(dir include src cli tools python tests examples)
  file(GLOB_RECURSE files LIST_DIRECTORIES false "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.h" "${ROOT}/${dir}/*.cpp"
       "${ROOT}/${dir}/*.cc")
  foreach(f IN LISTS files)
    file(RELATIVE_PATH rel "${ROOT}" "${f}")
    if(rel MATCHES "^src/cgal/")
      continue()
    endif()
    file(STRINGS "${f}" hits REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]CGAL/")
    if(hits)
      list(APPEND offenders "${rel}")
    endif()
  endforeach()
endforeach()
if(offenders)
  list(JOIN offenders "\n  " text)
  message(FATAL_ERROR "CGAL included outside src/cgal/:\n  ${text}")
endif()
message(STATUS "CGAL is included only under src/cgal/")
