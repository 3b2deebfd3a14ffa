# cmake -DSOURCE_DIR=... -DBINARY_DIR=... -P build_firmware.cmake: the firmware preset's
# build, configured first when it has never been.
if(NOT EXISTS ${BINARY_DIR}/build.ninja)
  execute_process(COMMAND ${CMAKE_COMMAND} --preset firmware WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the firmware preset failed")
  endif()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the firmware preset failed")
endif()
