#pragma once
// The Linux board's USB gadget in configfs (Documentation/usb/gadget_configfs.rst):
// /sys/kernel/config/usb_gadget/NAME with the board's VID:PID, bcdDevice and strings,
// one configuration holding one FunctionFS function ffs.NAME, mounted at
// /dev/ffs-NAME (or a given directory). The board writes its descriptors to that
// mount's ep0 (FfsFunction), then binds the gadget to a UDC. Reboots re-create it: the
// application (PID 0x0001) and the DFU-mode bootloader (PID 0x0002) are different devices.
#include <cstdint>
#include <string>

#include "tetrapulse/linux_board/board_error.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::linux_board {

struct UsbGadgetSpec {
  std::string name;           // configfs directory and FunctionFS instance name
  std::string mount_dir;      // where FunctionFS is mounted
  protocol::UsbMode mode = protocol::UsbMode::kApplication;
  uint16_t bcd_device = 0x0100;
  std::string serial;
  std::string udc;            // empty: the first UDC in /sys/class/udc
};

class UsbGadget {
 public:
  // Removes what a previous run left of gadget `spec.name` (unbound, unmounted, deleted),
  // then creates it and mounts FunctionFS. kUsbGadget naming the step that failed.
  BoardResult<void> create(const UsbGadgetSpec& spec);
  // Writes the UDC: the host sees the device. Call once ep0 has the descriptors.
  BoardResult<void> bind();
  // Unbinds, unmounts and deletes the gadget; quiet about what is already gone.
  void remove();
  const UsbGadgetSpec& spec() const { return spec_; }

 private:
  UsbGadgetSpec spec_;
};

}  // namespace tetrapulse::linux_board
