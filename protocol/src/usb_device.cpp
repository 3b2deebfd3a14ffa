#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol {

Result<size_t> encode_usb_protocol_info(const UsbProtocolInfo& info, uint8_t* out, size_t capacity) {
  ByteWriter w(out, capacity);
  w.u8(info.protocol_version);
  w.u8(0);
  w.u16(info.max_message_size);
  w.u32(info.capabilities);
  if (!w.ok()) return Error::kBufferTooSmall;
  return w.size();
}

Result<UsbProtocolInfo> decode_usb_protocol_info(ByteView in) {
  ByteReader r(in);
  UsbProtocolInfo info;
  info.protocol_version = r.u8();
  r.u8();  // reserved
  info.max_message_size = r.u16();
  info.capabilities = r.u32();
  if (!r.ok()) return r.error();
  return info;
}

}  // namespace tetrapulse::protocol
