#include "tetrapulse/protocol/dfu.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::protocol {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(DfuStatus, LayoutAndRoundTrip) {
  const DfuStatus s{DfuStatusCode::kErrVerify, 0x123456, DfuState::kDfuError, 5};
  uint8_t out[6];
  ASSERT_EQ(*encode_dfu_status(s, out, sizeof(out)), 6u);
  EXPECT_EQ(Bytes(out, out + 6), (Bytes{0x07, 0x56, 0x34, 0x12, 0x0A, 0x05}));
  const Result<DfuStatus> back = decode_dfu_status(ByteView{out, 6});
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, s);
}

TEST(DfuStatus, EveryDefinedStatusAndStateRoundTrips) {
  uint8_t out[6];
  for (uint8_t status = 0; status <= kDfuLastStatusCode; ++status) {
    for (uint8_t state = 0; state <= kDfuLastState; ++state) {
      const DfuStatus s{static_cast<DfuStatusCode>(status), kDfuMaxPollTimeoutMs - status,
                        static_cast<DfuState>(state), state};
      ASSERT_TRUE(encode_dfu_status(s, out, 6).ok());
      const Result<DfuStatus> back = decode_dfu_status(ByteView{out, 6});
      ASSERT_TRUE(back.ok());
      EXPECT_EQ(*back, s);
    }
  }
}

TEST(DfuStatus, RejectsUndefinedValuesAndWrongSizes) {
  uint8_t out[6];
  EXPECT_EQ(encode_dfu_status(DfuStatus{DfuStatusCode::kOk, 0x1000000, DfuState::kDfuIdle, 0}, out, 6).error(),
            Error::kBadValue);
  EXPECT_EQ(encode_dfu_status(DfuStatus{static_cast<DfuStatusCode>(0x10), 0, DfuState::kDfuIdle, 0}, out, 6).error(),
            Error::kBadValue);
  EXPECT_EQ(encode_dfu_status(DfuStatus{}, out, 5).error(), Error::kBufferTooSmall);
  const Bytes bad_status{0x10, 0, 0, 0, 2, 0}, bad_state{0, 0, 0, 0, 11, 0}, seven{0, 0, 0, 0, 2, 0, 0};
  EXPECT_EQ(decode_dfu_status(ByteView{bad_status.data(), 6}).error(), Error::kBadValue);
  EXPECT_EQ(decode_dfu_status(ByteView{bad_state.data(), 6}).error(), Error::kBadValue);
  EXPECT_EQ(decode_dfu_status(ByteView{seven.data(), 7}).error(), Error::kTrailingBytes);
  for (size_t n = 0; n < 6; ++n) EXPECT_EQ(decode_dfu_status(ByteView{seven.data(), n}).error(), Error::kTruncated);
}

TEST(UsbProtocolInfo, LayoutAndForwardCompatibility) {
  const UsbProtocolInfo info{1, 320, kUsbCapabilityBulkMessages | kUsbCapabilityDfuRuntime};
  uint8_t out[12] = {};
  ASSERT_EQ(*encode_usb_protocol_info(info, out, 8), 8u);
  EXPECT_EQ(Bytes(out, out + 8), (Bytes{1, 0, 0x40, 0x01, 0x05, 0, 0, 0}));
  // A later version may append fields: still readable.
  const Result<UsbProtocolInfo> longer = decode_usb_protocol_info(ByteView{out, 12});
  ASSERT_TRUE(longer.ok());
  EXPECT_EQ(*longer, info);
  EXPECT_EQ(decode_usb_protocol_info(ByteView{out, 7}).error(), Error::kTruncated);
  EXPECT_EQ(encode_usb_protocol_info(info, out, 7).error(), Error::kBufferTooSmall);
}

}  // namespace
}  // namespace tetrapulse::protocol
