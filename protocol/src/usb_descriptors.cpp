#include "tetrapulse/protocol/usb_descriptors.hpp"

#include "tetrapulse/protocol/bytes.hpp"

namespace tetrapulse::protocol {
namespace {

constexpr uint16_t kUsbVersionBcd = 0x0200;
constexpr uint8_t kConfigurationValue = 1;
constexpr uint8_t kConfigurationReservedBit = 0x80;  // bmAttributes D7 must be 1
constexpr uint8_t kConfigurationSelfPowered = 0x40;

Result<size_t> finish(const ByteWriter& w) {
  if (!w.ok()) return Error::kBufferTooSmall;
  return w.size();
}

void interface(ByteWriter& w, uint8_t number, uint8_t endpoints, uint8_t cls, uint8_t subclass,
               uint8_t protocol, uint8_t string_index) {
  w.u8(kUsbInterfaceDescriptorSize);
  w.u8(kUsbDescriptorInterface);
  w.u8(number);
  w.u8(0);  // bAlternateSetting
  w.u8(endpoints);
  w.u8(cls);
  w.u8(subclass);
  w.u8(protocol);
  w.u8(string_index);
}

void bulk_endpoint(ByteWriter& w, uint8_t address) {
  w.u8(kUsbEndpointDescriptorSize);
  w.u8(kUsbDescriptorEndpoint);
  w.u8(address);
  w.u8(kUsbEndpointBulk);
  w.u16(kUsbMaxPacketSize);
  w.u8(0);  // bInterval: ignored for full-speed bulk
}

void dfu_functional(ByteWriter& w, const UsbDeviceParams& p) {
  if (!p.dfu_functional_descriptor) return;
  w.u8(kDfuFunctionalDescriptorSize);
  w.u8(kDfuFunctionalDescriptorType);
  w.u8(p.dfu_attributes);
  w.u16(p.dfu_detach_timeout_ms);
  w.u16(p.dfu_transfer_size);
  w.u16(kDfuVersionBcd);
}

uint8_t interface_count(const UsbDeviceParams& p) { return p.mode == UsbMode::kApplication ? 2 : 1; }

}  // namespace

Result<size_t> build_usb_device_descriptor(const UsbDeviceParams& p, uint8_t* out, size_t capacity) {
  ByteWriter w(out, capacity);
  w.u8(kUsbDeviceDescriptorSize);
  w.u8(kUsbDescriptorDevice);
  w.u16(kUsbVersionBcd);
  w.u8(0);  // bDeviceClass: defined by each interface
  w.u8(0);
  w.u8(0);
  w.u8(kUsbMaxPacketSize);
  w.u16(kUsbVendorId);
  w.u16(p.mode == UsbMode::kApplication ? kUsbProductIdApplication : kUsbProductIdBootloader);
  w.u16(p.bcd_device);
  w.u8(kUsbStringManufacturer);
  w.u8(kUsbStringProduct);
  w.u8(kUsbStringSerial);
  w.u8(1);  // bNumConfigurations
  return finish(w);
}

Result<size_t> build_usb_function_descriptors(const UsbDeviceParams& p, uint8_t* out, size_t capacity) {
  ByteWriter w(out, capacity);
  if (p.mode == UsbMode::kApplication) {
    interface(w, kUsbMessageInterface, 2, kUsbMessageInterfaceClass, kUsbMessageInterfaceSubclass,
              kUsbMessageInterfaceProtocol, 0);
    bulk_endpoint(w, p.bulk_out_address);
    bulk_endpoint(w, p.bulk_in_address);
    interface(w, kUsbDfuRuntimeInterface, 0, kDfuInterfaceClass, kDfuInterfaceSubclass,
              kDfuProtocolRuntime, kUsbStringDfuInterface);
  } else {
    interface(w, 0, 0, kDfuInterfaceClass, kDfuInterfaceSubclass, kDfuProtocolDfuMode,
              kUsbStringDfuInterface);
  }
  dfu_functional(w, p);
  return finish(w);
}

Result<size_t> build_usb_configuration_descriptor(const UsbDeviceParams& p, uint8_t* out,
                                                  size_t capacity) {
  if (capacity < kUsbConfigurationHeaderSize) return Error::kBufferTooSmall;
  const Result<size_t> body = build_usb_function_descriptors(
      p, out + kUsbConfigurationHeaderSize, capacity - kUsbConfigurationHeaderSize);
  if (!body) return body.error();
  const size_t total = kUsbConfigurationHeaderSize + *body;
  ByteWriter w(out, kUsbConfigurationHeaderSize);
  w.u8(kUsbConfigurationHeaderSize);
  w.u8(kUsbDescriptorConfiguration);
  w.u16(static_cast<uint16_t>(total));
  w.u8(interface_count(p));
  w.u8(kConfigurationValue);
  w.u8(0);  // iConfiguration
  w.u8(static_cast<uint8_t>(kConfigurationReservedBit | (p.self_powered ? kConfigurationSelfPowered : 0)));
  w.u8(p.max_power_2ma);
  if (!w.ok()) return Error::kBufferTooSmall;
  return total;
}

Result<size_t> build_usb_language_descriptor(uint8_t* out, size_t capacity) {
  ByteWriter w(out, capacity);
  w.u8(4);
  w.u8(kUsbDescriptorString);
  w.u16(kUsbLanguageEnglishUs);
  return finish(w);
}

Result<size_t> build_usb_string_descriptor(const char* ascii, uint8_t* out, size_t capacity) {
  constexpr size_t kMaxChars = (255 - 2) / 2;
  size_t length = 0;
  while (ascii[length] != '\0') {
    if (static_cast<unsigned char>(ascii[length]) > 0x7F || length == kMaxChars) return Error::kBadValue;
    ++length;
  }
  ByteWriter w(out, capacity);
  w.u8(static_cast<uint8_t>(2 + 2 * length));
  w.u8(kUsbDescriptorString);
  for (size_t i = 0; i < length; ++i) w.u16(static_cast<unsigned char>(ascii[i]));
  return finish(w);
}

}  // namespace tetrapulse::protocol
