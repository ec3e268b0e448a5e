# Fails if a file under Readers/ includes a header of Filters/: the conversions both use live in
# the Bridge/ module (CraterKit::Bridge), so that Readers depends on Filters in no way
# (docs/architecture.md, "Modules and layers"). A header counts as Filters' when its path names
# Filters/ or its file name is one of the headers in Filters/.
#   cmake -DSOURCE_DIR=<tree> -P CheckReadersNoFilters.cmake
file(GLOB_RECURSE sources "${SOURCE_DIR}/Readers/*.h" "${SOURCE_DIR}/Readers/*.hpp"
     "${SOURCE_DIR}/Readers/*.cpp" "${SOURCE_DIR}/Readers/*.cxx" "${SOURCE_DIR}/Readers/*.txx")
if(NOT sources)
  message(FATAL_ERROR "no sources found under ${SOURCE_DIR}/Readers")
endif()
file(GLOB_RECURSE filter_headers RELATIVE "${SOURCE_DIR}/Filters"
     "${SOURCE_DIR}/Filters/*.h" "${SOURCE_DIR}/Filters/*.hpp" "${SOURCE_DIR}/Filters/*.txx")
set(filter_names "")
foreach(h IN LISTS filter_headers)
  get_filename_component(name "${h}" NAME)
  list(APPEND filter_names "${name}")
endforeach()
set(offenders "")
foreach(f IN LISTS sources)
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"].*" "\\1" header "${line}")
    get_filename_component(name "${header}" NAME)
    list(FIND filter_names "${name}" at)
    if(header MATCHES "(^|/)Filters/" OR at GREATER -1)
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
      list(APPEND offenders "${rel}: #include \"${header}\"")
    endif()
  endforeach()
endforeach()
if(offenders)
  string(REPLACE ";" "\n" offenders "${offenders}")
  message(FATAL_ERROR "Readers/ must not include headers of Filters/ (use Bridge/):\n${offenders}")
endif()
list(LENGTH sources count)
message(STATUS "${count} reader files checked: no Filters/ includes")
