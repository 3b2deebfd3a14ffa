# USB device (control endpoint, message interface), the DFU 1.1 state machine and the
# bootloader's update paths (DFU bundle writer, CAN requests): hardware-independent parts
# of the STM32 USB and bootloader work, also driven by the Linux board's FunctionFS gadget.
target_sources(tetrapulse_fw_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/bootloader_command_handler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/dfu_device.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/image_bundle_writer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/update_slot.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/usb_control.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/usb_endpoint_zero.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/usb_message_function.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/usb_setup.cpp
)
