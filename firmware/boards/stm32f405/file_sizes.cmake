# cmake -DFILES=a:b -P file_sizes.cmake: prints the size of each file the build hands out
# (colons between the paths: a shell would split a custom command at semicolons).
string(REPLACE ":" ";" files "${FILES}")
foreach(f IN LISTS files)
  if(NOT EXISTS ${f})
    message(FATAL_ERROR "${f} was not written")
  endif()
  file(SIZE ${f} bytes)
  get_filename_component(name ${f} NAME)
  message(STATUS "${name}: ${bytes} bytes")
endforeach()
