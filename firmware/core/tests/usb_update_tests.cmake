# Tests of the USB device, DFU and bootloader update parts of the core (usb_update.cmake).
add_library(tetrapulse_fw_usb_testing STATIC usb_test_host.cpp dfu_util_model.cpp)
target_include_directories(tetrapulse_fw_usb_testing PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(tetrapulse_fw_usb_testing PUBLIC tetrapulse::fw_core GTest::gtest PRIVATE tetrapulse_warnings)

tetrapulse_test(fw_usb_control_test SOURCES usb_control_test.cpp
  LIBS tetrapulse_fw_usb_testing tetrapulse_protocol_vectors)
tetrapulse_test(fw_usb_endpoint_zero_test SOURCES usb_endpoint_zero_test.cpp
  LIBS tetrapulse_fw_usb_testing rapidcheck rapidcheck_gtest)
tetrapulse_test(fw_dfu_device_test SOURCES dfu_device_test.cpp
  LIBS tetrapulse_fw_usb_testing rapidcheck rapidcheck_gtest)
tetrapulse_test(fw_image_bundle_writer_test SOURCES image_bundle_writer_test.cpp
  LIBS tetrapulse_fw_usb_testing tetrapulse::sim_board rapidcheck rapidcheck_gtest)
tetrapulse_test(fw_bootloader_command_handler_test SOURCES bootloader_command_handler_test.cpp
  LIBS tetrapulse::fw_core tetrapulse::sim_board)
