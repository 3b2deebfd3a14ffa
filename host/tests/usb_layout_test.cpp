// parse_usb_layout on the golden descriptors of protocol/vectors/usb, on renumbered
// endpoints, and on broken input (never crashes, names what is wrong).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "tetrapulse/host/usb_layout.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "vector_file.hpp"

namespace tetrapulse::host {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes configuration_vector(const std::string& name) {
  auto f = protocol::testing::read_vector_file(protocol::testing::vectors_dir("usb") + "/" + name);
  EXPECT_TRUE(f.has_value());
  return f ? f->first("configuration")->bytes : Bytes{};
}

HostResult<UsbLayout> parse(const Bytes& b) { return parse_usb_layout(protocol::ByteView{b.data(), b.size()}); }

TEST(UsbLayout, ApplicationHasMessagesAndDfuRuntime) {
  auto layout = parse(configuration_vector("descriptors_application.txt"));
  ASSERT_TRUE(layout) << layout.error().what();
  ASSERT_TRUE(layout->messages);
  EXPECT_EQ(layout->messages->number, 0);
  EXPECT_EQ(layout->messages->bulk_out, 0x01);
  EXPECT_EQ(layout->messages->bulk_in, 0x81);
  EXPECT_EQ(layout->messages->in_packet_size, 64);
  ASSERT_TRUE(layout->dfu);
  EXPECT_EQ(layout->dfu->number, 1);
  EXPECT_FALSE(layout->dfu->dfu_mode);
  ASSERT_TRUE(layout->dfu->functional);
  EXPECT_EQ(layout->dfu->functional->attributes, 0x0D);
  EXPECT_EQ(layout->dfu->functional->detach_timeout_ms, 1000);
  EXPECT_EQ(layout->dfu->functional->transfer_size, 1024);
  EXPECT_EQ(layout->dfu->functional->dfu_version, 0x0110);
}

TEST(UsbLayout, BootloaderIsDfuModeOnly) {
  auto layout = parse(configuration_vector("descriptors_bootloader.txt"));
  ASSERT_TRUE(layout) << layout.error().what();
  EXPECT_FALSE(layout->messages);
  ASSERT_TRUE(layout->dfu);
  EXPECT_TRUE(layout->dfu->dfu_mode);
  EXPECT_EQ(layout->dfu->number, 0);
  ASSERT_TRUE(layout->dfu->functional);
  EXPECT_EQ(layout->dfu->functional->transfer_size, 1024);
}

TEST(UsbLayout, Linux61GadgetHasNoFunctionalDescriptor) {
  auto layout = parse(configuration_vector("descriptors_gadget_linux61.txt"));
  ASSERT_TRUE(layout) << layout.error().what();
  ASSERT_TRUE(layout->messages);
  ASSERT_TRUE(layout->dfu);
  EXPECT_FALSE(layout->dfu->functional);
}

TEST(UsbLayout, EndpointAddressesAreReadNotAssumed) {
  protocol::UsbDeviceParams p;
  p.bulk_out_address = 0x02;
  p.bulk_in_address = 0x83;
  uint8_t buffer[protocol::kUsbMaxConfigurationSize];
  auto size = protocol::build_usb_configuration_descriptor(p, buffer, sizeof(buffer));
  ASSERT_TRUE(size.ok());
  auto layout = parse(Bytes(buffer, buffer + *size));
  ASSERT_TRUE(layout && layout->messages);
  EXPECT_EQ(layout->messages->bulk_out, 0x02);
  EXPECT_EQ(layout->messages->bulk_in, 0x83);
}

TEST(UsbLayout, EveryTruncationIsRefused) {
  const Bytes whole = configuration_vector("descriptors_application.txt");
  for (size_t n = 0; n < whole.size(); ++n) {
    Bytes cut(whole.begin(), whole.begin() + static_cast<long>(n));
    if (n >= 4) {  // keep wTotalLength honest so the descriptor walk itself is tested
      cut[2] = static_cast<uint8_t>(n);
      cut[3] = 0;
    }
    auto layout = parse(cut);
    if (layout) {
      EXPECT_FALSE(layout->messages && layout->dfu && layout->dfu->functional) << "a cut at " << n;
    } else {
      EXPECT_EQ(layout.error().kind, HostErrorKind::kMalformed);
    }
  }
}

TEST(UsbLayout, ZeroLengthDescriptorIsRefused) {
  Bytes b = configuration_vector("descriptors_application.txt");
  b[9] = 0;  // interface 0's bLength
  auto layout = parse(b);
  ASSERT_FALSE(layout);
  EXPECT_NE(layout.error().message.find("offset 9"), std::string::npos) << layout.error().message;
}

RC_GTEST_PROP(UsbLayout, AnyBytesGiveALayoutOrAnError, (std::vector<uint8_t> tail)) {
  Bytes b = configuration_vector("descriptors_application.txt");
  b.resize(9);
  b.insert(b.end(), tail.begin(), tail.end());
  b[2] = static_cast<uint8_t>(b.size());
  b[3] = static_cast<uint8_t>(b.size() >> 8);
  auto layout = parse(b);
  if (layout && layout->messages) RC_ASSERT(layout->messages->bulk_in != 0 && layout->messages->bulk_out != 0);
}

}  // namespace
}  // namespace tetrapulse::host
