#include "tetrapulse/protocol/usb_descriptors.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes build(Result<size_t> (*fn)(const UsbDeviceParams&, uint8_t*, size_t), const UsbDeviceParams& p) {
  Bytes out(256);
  const Result<size_t> n = fn(p, out.data(), out.size());
  EXPECT_TRUE(n.ok());
  out.resize(n.ok() ? *n : 0);
  return out;
}

// Field by field from USB 2.0 table 9-8.
TEST(UsbDescriptors, DeviceDescriptor) {
  UsbDeviceParams p;
  p.bcd_device = 0x0123;
  const Bytes d = build(build_usb_device_descriptor, p);
  const Bytes expected = {
      18, 1,        // bLength, DEVICE
      0x00, 0x02,   // bcdUSB 2.00
      0, 0, 0,      // class, subclass, protocol: per interface
      64,           // bMaxPacketSize0
      0x09, 0x12,   // idVendor 0x1209
      0x01, 0x00,   // idProduct 0x0001
      0x23, 0x01,   // bcdDevice
      1, 2, 3,      // iManufacturer, iProduct, iSerialNumber
      1};           // bNumConfigurations
  EXPECT_EQ(d, expected);
  p.mode = UsbMode::kBootloader;
  const Bytes b = build(build_usb_device_descriptor, p);
  EXPECT_EQ(b[10], 0x02);
  EXPECT_EQ(b[11], 0x00);
}

// Tables 9-10, 9-12, 9-13 and DFU 1.1 table 4.2.
TEST(UsbDescriptors, ApplicationConfiguration) {
  const UsbDeviceParams p;
  const Bytes c = build(build_usb_configuration_descriptor, p);
  const Bytes expected = {
      9, 2, 50, 0, 2, 1, 0, 0x80, 50,          // configuration: wTotalLength 50, 2 interfaces, bus powered, 100 mA
      9, 4, 0, 0, 2, 0xFF, 0x54, 0x01, 0,      // interface 0: vendor, 2 endpoints
      7, 5, 0x01, 0x02, 64, 0, 0,              // bulk OUT 1, 64 bytes
      7, 5, 0x81, 0x02, 64, 0, 0,              // bulk IN 1, 64 bytes
      9, 4, 1, 0, 0, 0xFE, 0x01, 0x01, 4,      // interface 1: DFU run-time, string 4
      9, 0x21, 0x0D, 0xE8, 0x03, 0x00, 0x04, 0x10, 0x01};  // DFU functional: 1000 ms, 1024 B, DFU 1.1
  EXPECT_EQ(c, expected);
  EXPECT_LE(c.size(), kUsbMaxConfigurationSize);
}

TEST(UsbDescriptors, BootloaderConfiguration) {
  UsbDeviceParams p;
  p.mode = UsbMode::kBootloader;
  p.self_powered = true;
  p.max_power_2ma = 0;
  p.dfu_transfer_size = 2048;
  const Bytes c = build(build_usb_configuration_descriptor, p);
  const Bytes expected = {
      9, 2, 27, 0, 1, 1, 0, 0xC0, 0,
      9, 4, 0, 0, 0, 0xFE, 0x01, 0x02, 4,
      9, 0x21, 0x0D, 0xE8, 0x03, 0x00, 0x08, 0x10, 0x01};
  EXPECT_EQ(c, expected);
}

TEST(UsbDescriptors, WalkingTheConfigurationFindsEveryDescriptor) {
  for (bool functional : {true, false}) {
    UsbDeviceParams p;
    p.dfu_functional_descriptor = functional;
    p.bulk_out_address = 0x02;  // as a UDC renumbered them
    p.bulk_in_address = 0x83;
    const Bytes c = build(build_usb_configuration_descriptor, p);
    ASSERT_EQ(c[2] | (c[3] << 8), static_cast<int>(c.size()));
    int interfaces = 0, endpoints = 0, dfu = 0;
    std::vector<uint8_t> addresses;
    for (size_t at = 0; at < c.size(); at += c[at]) {
      ASSERT_GE(c[at], 2);
      if (c[at + 1] == kUsbDescriptorInterface) ++interfaces;
      if (c[at + 1] == kUsbDescriptorEndpoint) {
        ++endpoints;
        addresses.push_back(c[at + 2]);
      }
      if (c[at + 1] == kDfuFunctionalDescriptorType) ++dfu;
    }
    EXPECT_EQ(interfaces, c[4]);
    EXPECT_EQ(endpoints, 2);
    EXPECT_EQ(addresses, (std::vector<uint8_t>{0x02, 0x83}));
    EXPECT_EQ(dfu, functional ? 1 : 0);
    EXPECT_EQ(c.size(), functional ? 50u : 41u);
  }
}

TEST(UsbDescriptors, FunctionDescriptorsAreTheConfigurationWithoutItsHeader) {
  for (UsbMode mode : {UsbMode::kApplication, UsbMode::kBootloader}) {
    UsbDeviceParams p;
    p.mode = mode;
    const Bytes c = build(build_usb_configuration_descriptor, p);
    const Bytes f = build(build_usb_function_descriptors, p);
    EXPECT_EQ(Bytes(c.begin() + kUsbConfigurationHeaderSize, c.end()), f);
  }
}

TEST(UsbDescriptors, ShortBuffersAreRefused) {
  const UsbDeviceParams p;
  uint8_t out[64];
  for (size_t cap = 0; cap < 50; ++cap) {
    EXPECT_EQ(build_usb_configuration_descriptor(p, out, cap).error(), Error::kBufferTooSmall) << cap;
  }
  for (size_t cap = 0; cap < 18; ++cap) {
    EXPECT_EQ(build_usb_device_descriptor(p, out, cap).error(), Error::kBufferTooSmall) << cap;
  }
}

TEST(UsbDescriptors, Strings) {
  uint8_t out[256];
  ASSERT_EQ(*build_usb_language_descriptor(out, sizeof(out)), 4u);
  EXPECT_EQ(Bytes(out, out + 4), (Bytes{4, 3, 0x09, 0x04}));
  ASSERT_EQ(*build_usb_string_descriptor(kUsbProductString, out, sizeof(out)), 22u);
  EXPECT_EQ(Bytes(out, out + 6), (Bytes{22, 3, 't', 0, 'e', 0}));
  EXPECT_EQ(*build_usb_string_descriptor("", out, sizeof(out)), 2u);
  EXPECT_EQ(build_usb_string_descriptor("caf\xc3\xa9", out, sizeof(out)).error(), Error::kBadValue);
  const std::string longest(126, 'x');
  EXPECT_EQ(*build_usb_string_descriptor(longest.c_str(), out, sizeof(out)), 254u);
  const std::string too_long(127, 'x');
  EXPECT_EQ(build_usb_string_descriptor(too_long.c_str(), out, sizeof(out)).error(), Error::kBadValue);
  EXPECT_EQ(build_usb_string_descriptor("tetrapulse", out, 21).error(), Error::kBufferTooSmall);
}

}  // namespace
}  // namespace tetrapulse::protocol
