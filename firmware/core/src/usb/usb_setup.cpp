#include "tetrapulse/fw/usb/usb_setup.hpp"

namespace tetrapulse::fw {

UsbSetup decode_usb_setup(const uint8_t (&packet)[kUsbSetupSize]) {
  UsbSetup s;
  s.request_type = packet[0];
  s.request = packet[1];
  s.value = static_cast<uint16_t>(packet[2] | packet[3] << 8);
  s.index = static_cast<uint16_t>(packet[4] | packet[5] << 8);
  s.length = static_cast<uint16_t>(packet[6] | packet[7] << 8);
  return s;
}

void encode_usb_setup(const UsbSetup& setup, uint8_t (&packet)[kUsbSetupSize]) {
  packet[0] = setup.request_type;
  packet[1] = setup.request;
  packet[2] = static_cast<uint8_t>(setup.value);
  packet[3] = static_cast<uint8_t>(setup.value >> 8);
  packet[4] = static_cast<uint8_t>(setup.index);
  packet[5] = static_cast<uint8_t>(setup.index >> 8);
  packet[6] = static_cast<uint8_t>(setup.length);
  packet[7] = static_cast<uint8_t>(setup.length >> 8);
}

}  // namespace tetrapulse::fw
