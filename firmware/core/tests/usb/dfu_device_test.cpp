// The DFU 1.1 state machine driven the way dfu-util 0.11 drives it (dfu_util_model.hpp),
// both behind the bootloader's own control endpoint in 64-byte packets (STM32) and
// straight through the function (a FunctionFS gadget): downloads of every size arrive
// intact block by block, the states follow DFU 1.1 appendix A, and every refusal and
// failure ends in dfuERROR with the status the host needs, from which CLRSTATUS recovers.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <vector>

#include "dfu_util_model.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/fw/usb/usb_control.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;
using tp::DfuRequest;
using tp::DfuState;
using tp::DfuStatusCode;

// A download target that keeps what it is given and fails when told to.
class RecordingTarget final : public DfuDownloadTarget {
 public:
  std::vector<uint8_t> file;
  std::vector<uint32_t> offsets;
  int manifests = 0;
  int aborts = 0;
  uint32_t manifested_size = 0;
  size_t fail_block = SIZE_MAX;  // download() of this block fails with fail_status
  DfuStatusCode fail_status = DfuStatusCode::kErrProg;
  DfuStatusCode manifest_status = DfuStatusCode::kOk;
  uint32_t poll_ms = 5;
  uint32_t erase_ms = 1500;
  std::vector<uint8_t> readable;  // what UPLOAD reads

 private:
  DfuStatusCode do_download(uint32_t offset, tp::ByteView block) override {
    if (offset == 0) file.clear();
    if (offsets.size() == fail_block) {
      offsets.push_back(offset);
      return fail_status;
    }
    offsets.push_back(offset);
    EXPECT_EQ(offset, file.size()) << "blocks out of order";
    file.insert(file.end(), block.begin(), block.end());
    return DfuStatusCode::kOk;
  }
  uint32_t do_download_poll_ms(uint32_t offset, size_t) const override { return offset == 0 ? erase_ms : poll_ms; }
  DfuStatusCode do_manifest(uint32_t size) override {
    ++manifests;
    manifested_size = size;
    return manifest_status;
  }
  uint32_t do_manifest_poll_ms() const override { return 50; }
  void do_abort() override { ++aborts; }
  tp::Result<size_t> do_upload(uint32_t offset, uint8_t* out, size_t capacity) override {
    if (offset > readable.size()) return tp::Error::kBadValue;
    const size_t n = std::min(capacity, readable.size() - offset);
    std::copy(readable.begin() + offset, readable.begin() + static_cast<std::ptrdiff_t>(offset + n), out);
    return n;
  }
};

class CountingDetach final : public DfuRuntimeTarget {
 public:
  int detaches = 0;

 private:
  void do_detach() override { ++detaches; }
};

enum class Stack { kPackets, kFunction };

tp::UsbDeviceParams dfu_mode(uint16_t transfer_size = 1024, uint8_t attributes = tp::kDfuDefaultAttributes) {
  tp::UsbDeviceParams p;
  p.mode = tp::UsbMode::kBootloader;
  p.dfu_transfer_size = transfer_size;
  p.dfu_attributes = attributes;
  return p;
}

// A DFU-mode device (the bootloader's interface 0) and dfu-util talking to it.
struct Bootloader {
  Bootloader(Stack stack, const tp::UsbDeviceParams& p)
      : params(p), block(p.dfu_transfer_size), dfu(target, params, block.data(), block.size()),
        control(params, "SERIAL", controller, buffer, sizeof(buffer)) {
    control.set_function(0, dfu);
    if (stack == Stack::kPackets) {
      auto h = std::make_unique<PacketHost>(control);
      enumerate(*h, controller);
      EXPECT_FALSE(h->out(standard_out(UsbRecipient::kInterface, usb_request::kSetInterface, 0, 0), {}).stalled);
      host = std::move(h);
    } else {
      host = std::make_unique<FunctionHost>(dfu);
    }
    util = std::make_unique<DfuUtilModel>(*host, 0, p.dfu_transfer_size, [this](uint32_t ms) {
      now += ms;
      dfu.poll(now);  // the bootloader's main loop runs while the host sleeps
    });
  }
  ControlResult request_out(DfuRequest r, uint16_t length = 0, std::vector<uint8_t> data = {}) {
    return host->out(class_out(static_cast<uint8_t>(r), 0, 0, length), data);
  }
  ControlResult request_in(DfuRequest r, uint16_t length) {
    return host->in(class_in(static_cast<uint8_t>(r), 0, 0, length));
  }

  tp::UsbDeviceParams params;
  RecordingTarget target;
  std::vector<uint8_t> block;
  DfuDevice dfu;
  RecordingController controller;
  uint8_t buffer[1024] = {};
  UsbControl control;
  std::unique_ptr<ControlPipe> host;
  std::unique_ptr<DfuUtilModel> util;
  uint32_t now = 0;
};

std::vector<uint8_t> pattern(size_t n, uint32_t seed = 1) {
  std::vector<uint8_t> v(n);
  uint32_t x = seed * 2654435761u + 1;
  for (auto& b : v) {
    x = x * 1103515245u + 12345u;
    b = static_cast<uint8_t>(x >> 16);
  }
  return v;
}

class DfuMode : public ::testing::TestWithParam<Stack> {};

TEST_P(DfuMode, DfuUtilDownloadArrivesIntactThroughTheDocumentedStates) {
  Bootloader b(GetParam(), dfu_mode());
  const std::vector<uint8_t> file = pattern(5000);
  ASSERT_TRUE(b.util->download(file)) << b.util->error;
  EXPECT_EQ(b.target.file, file);
  EXPECT_EQ(b.target.offsets, (std::vector<uint32_t>{0, 1024, 2048, 3072, 4096}));
  EXPECT_EQ(b.target.manifests, 1);
  EXPECT_EQ(b.target.manifested_size, 5000u);
  EXPECT_EQ(b.target.aborts, 0);
  EXPECT_EQ(b.util->block_numbers, (std::vector<uint16_t>{0, 1, 2, 3, 4, 5}));
  std::vector<DfuState> expected{DfuState::kDfuIdle};
  for (int i = 0; i < 5; ++i) {
    expected.push_back(DfuState::kDfuDownloadBusy);
    expected.push_back(DfuState::kDfuDownloadIdle);
  }
  expected.push_back(DfuState::kDfuManifest);
  expected.push_back(DfuState::kDfuIdle);
  EXPECT_EQ(b.util->states, expected);
  EXPECT_TRUE(b.dfu.installed());
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuIdle);
  // The host was told to wait for the erase with the first block, then the writes.
  EXPECT_EQ(b.util->slept_ms, 1500u + 4 * 5 + 50 + 1000);
}

TEST_P(DfuMode, StatusAnswersCarryThePollTimeoutOfTheWorkAhead) {
  Bootloader b(GetParam(), dfu_mode());
  EXPECT_FALSE(b.request_out(DfuRequest::kDownload, 100, pattern(100)).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuDownloadSync);
  const ControlResult busy = b.request_in(DfuRequest::kGetStatus, 6);
  EXPECT_EQ(busy.data, (std::vector<uint8_t>{0x00, 0xDC, 0x05, 0x00, 0x04, 0x00})) << "OK, 1500 ms, dfuDNBUSY";
  EXPECT_TRUE(b.target.file.empty()) << "the write waits for the main loop";
  b.dfu.poll(1);
  EXPECT_EQ(b.target.file.size(), 100u);
  EXPECT_EQ(b.request_in(DfuRequest::kGetState, 1).data, (std::vector<uint8_t>{3})) << "dfuDNLOAD-SYNC";
  EXPECT_EQ(b.request_in(DfuRequest::kGetStatus, 6).data, (std::vector<uint8_t>{0, 0, 0, 0, 0x05, 0}));
}

TEST_P(DfuMode, AHostThatDoesNotWaitIsStalledIntoError) {
  Bootloader b(GetParam(), dfu_mode());
  b.request_out(DfuRequest::kDownload, 64, pattern(64));
  b.request_in(DfuRequest::kGetStatus, 6);  // dfuDNBUSY: wait 1500 ms
  EXPECT_TRUE(b.request_in(DfuRequest::kGetStatus, 6).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuError);
  EXPECT_EQ(b.dfu.status(), DfuStatusCode::kErrStalledPacket);
  EXPECT_EQ(b.target.aborts, 1);
  b.dfu.poll(2000);
  EXPECT_TRUE(b.target.file.empty()) << "the abandoned block is never written";
  // dfu-util's next session clears the error and starts over.
  const std::vector<uint8_t> file = pattern(700, 3);
  ASSERT_TRUE(b.util->download(file)) << b.util->error;
  EXPECT_EQ(b.target.file, file);
}

TEST_P(DfuMode, WriteFailureReportsTheTargetsStatus) {
  Bootloader b(GetParam(), dfu_mode());
  b.target.fail_block = 2;
  b.target.fail_status = DfuStatusCode::kErrProg;
  EXPECT_FALSE(b.util->download(pattern(4000)));
  EXPECT_EQ(b.util->last.state, DfuState::kDfuError);
  EXPECT_EQ(b.util->last.status, DfuStatusCode::kErrProg);
  EXPECT_EQ(b.target.aborts, 1);
  EXPECT_EQ(b.target.manifests, 0);
  EXPECT_FALSE(b.dfu.installed());
  EXPECT_FALSE(b.request_out(DfuRequest::kClearStatus).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuIdle);
  EXPECT_EQ(b.dfu.status(), DfuStatusCode::kOk);
}

TEST_P(DfuMode, ManifestationVerdictIsTheTargetsStatus) {
  Bootloader b(GetParam(), dfu_mode());
  b.target.manifest_status = DfuStatusCode::kErrVerify;
  EXPECT_FALSE(b.util->download(pattern(2048)));
  EXPECT_EQ(b.util->last.state, DfuState::kDfuError);
  EXPECT_EQ(b.util->last.status, DfuStatusCode::kErrVerify);
  EXPECT_EQ(b.util->states.back(), DfuState::kDfuError);
  EXPECT_FALSE(b.dfu.installed());
  // The next attempt starts with CLRSTATUS (dfu-util's session start) and succeeds.
  b.target.manifest_status = DfuStatusCode::kOk;
  DfuUtilModel again(*b.host, 0, 1024, [&](uint32_t ms) { b.dfu.poll(b.now += ms); });
  ASSERT_TRUE(again.download(pattern(2048))) << again.error;
  EXPECT_TRUE(b.dfu.installed());
}

TEST_P(DfuMode, WithoutManifestationToleranceItWaitsForTheReset) {
  Bootloader b(GetParam(), dfu_mode(1024, tp::kDfuCanDownload | tp::kDfuWillDetach));
  ASSERT_TRUE(b.util->download(pattern(1500))) << b.util->error;
  EXPECT_EQ(b.util->states.back(), DfuState::kDfuManifestWaitReset);
  EXPECT_TRUE(b.dfu.installed()) << "dfu-util reset the bus after dfuMANIFEST-WAIT-RESET";
}

TEST_P(DfuMode, AbortEndsADownloadAndTheTargetHearsOfIt) {
  Bootloader b(GetParam(), dfu_mode());
  b.request_out(DfuRequest::kDownload, 512, pattern(512));
  b.request_in(DfuRequest::kGetStatus, 6);
  b.dfu.poll(1);
  b.request_in(DfuRequest::kGetStatus, 6);
  ASSERT_EQ(b.dfu.state(), DfuState::kDfuDownloadIdle);
  EXPECT_FALSE(b.request_out(DfuRequest::kAbort).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuIdle);
  EXPECT_EQ(b.target.aborts, 1);
  EXPECT_TRUE(b.request_out(DfuRequest::kDownload).stalled) << "a zero-length DNLOAD with nothing downloaded";
  EXPECT_EQ(b.dfu.status(), DfuStatusCode::kErrStalledPacket);
}

TEST_P(DfuMode, RefusalsStallAndEnterError) {
  Bootloader b(GetParam(), dfu_mode(256));
  // Longer than wTransferSize.
  EXPECT_TRUE(b.request_out(DfuRequest::kDownload, 257, pattern(257)).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuError);
  EXPECT_EQ(b.dfu.status(), DfuStatusCode::kErrStalledPacket);
  // In dfuERROR only GETSTATUS, GETSTATE and CLRSTATUS work.
  EXPECT_EQ(b.request_in(DfuRequest::kGetStatus, 6).data, (std::vector<uint8_t>{0x0F, 0, 0, 0, 0x0A, 0}));
  EXPECT_TRUE(b.request_out(DfuRequest::kAbort).stalled);
  EXPECT_EQ(b.dfu.status(), DfuStatusCode::kErrStalledPacket);
  EXPECT_FALSE(b.request_out(DfuRequest::kClearStatus).stalled);
  // DETACH means nothing in DFU mode; UPLOAD is not offered (bitCanUpload clear).
  EXPECT_TRUE(b.request_out(DfuRequest::kDetach).stalled);
  b.request_out(DfuRequest::kClearStatus);
  EXPECT_TRUE(b.request_in(DfuRequest::kUpload, 256).stalled);
  b.request_out(DfuRequest::kClearStatus);
  // CLRSTATUS outside dfuERROR is an error itself.
  EXPECT_TRUE(b.request_out(DfuRequest::kClearStatus).stalled);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuError);
}

TEST_P(DfuMode, UsbResetEndsADownloadInProgress) {
  Bootloader b(GetParam(), dfu_mode());
  b.request_out(DfuRequest::kDownload, 100, pattern(100));
  b.host->bus_reset();
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuIdle);
  EXPECT_EQ(b.target.aborts, 1);
  EXPECT_FALSE(b.dfu.installed());
}

TEST_P(DfuMode, UploadReadsTheTargetInTransferSizeBlocks) {
  Bootloader b(GetParam(), dfu_mode(1024, tp::kDfuDefaultAttributes | tp::kDfuCanUpload));
  b.target.readable = pattern(3000, 9);
  const auto file = b.util->upload();
  ASSERT_TRUE(file.has_value()) << b.util->error;
  EXPECT_EQ(*file, b.target.readable);
  EXPECT_EQ(b.dfu.state(), DfuState::kDfuIdle) << "a short block ends the upload";
}

INSTANTIATE_TEST_SUITE_P(BothStacks, DfuMode, ::testing::Values(Stack::kPackets, Stack::kFunction),
                         [](const auto& p) { return p.param == Stack::kPackets ? "Packets" : "Function"; });

RC_GTEST_PROP(DfuMode, AnyFileAndTransferSizeArrivesIntact, ()) {
  const auto size = *rc::gen::inRange<size_t>(1, 6000);
  const auto transfer = *rc::gen::element<uint16_t>(64, 100, 256, 1000, 1024, 2048);
  const auto stack = *rc::gen::element(Stack::kPackets, Stack::kFunction);
  Bootloader b(stack, dfu_mode(transfer));
  const std::vector<uint8_t> file = pattern(size, static_cast<uint32_t>(size));
  RC_ASSERT(b.util->download(file));
  RC_ASSERT(b.target.file == file);
  RC_ASSERT(b.target.manifested_size == size);
  RC_ASSERT(b.dfu.installed());
}

RC_GTEST_PROP(DfuMode, ArbitraryRequestsKeepADefinedStateAndCLRSTATUSRecovers, ()) {
  Bootloader b(Stack::kFunction, dfu_mode(256, tp::kDfuDefaultAttributes | tp::kDfuCanUpload));
  b.target.readable = pattern(1000);
  const auto steps = *rc::gen::container<std::vector<std::tuple<uint8_t, uint16_t, bool, bool>>>(
      rc::gen::tuple(rc::gen::inRange<uint8_t>(0, 9), rc::gen::inRange<uint16_t>(0, 300), rc::gen::arbitrary<bool>(),
                     rc::gen::arbitrary<bool>()));
  for (const auto& [request, length, in, poll] : steps) {
    if (in) {
      b.host->in(class_in(request, 0, 0, length));
    } else {
      b.host->out(class_out(request, 0, 0, length), pattern(length));
    }
    if (poll) b.dfu.poll(b.now += 10);
    const auto state = static_cast<uint8_t>(b.dfu.state());
    RC_ASSERT(state >= static_cast<uint8_t>(DfuState::kDfuIdle));
    RC_ASSERT(state <= tp::kDfuLastState);
    RC_ASSERT(static_cast<uint8_t>(b.dfu.status()) <= tp::kDfuLastStatusCode);
  }
  // What a host does to get back to dfuIDLE from wherever the device was left: wait out
  // the work it was told about, clear an error, abort a transfer.
  for (int i = 0; i < 4 && !(b.dfu.state() == DfuState::kDfuIdle && b.dfu.status() == DfuStatusCode::kOk); ++i) {
    b.dfu.poll(b.now += 5000);
    const ControlResult s = b.request_in(DfuRequest::kGetStatus, 6);
    RC_ASSERT(!s.stalled);
    b.dfu.poll(b.now += 5000);
    if (b.dfu.state() == DfuState::kDfuError) b.request_out(DfuRequest::kClearStatus);
    if (b.dfu.state() == DfuState::kDfuDownloadIdle || b.dfu.state() == DfuState::kDfuUploadIdle) {
      b.request_out(DfuRequest::kAbort);
    }
  }
  RC_ASSERT(b.dfu.state() == DfuState::kDfuIdle);
  RC_ASSERT(b.util->download(pattern(600)));
}

// Run-time mode: the application's interface 1.
struct Application {
  explicit Application(uint8_t attributes = tp::kDfuDefaultAttributes) : dfu(detach, params(attributes)), host(dfu) {}
  static tp::UsbDeviceParams params(uint8_t attributes) {
    tp::UsbDeviceParams p;
    p.dfu_attributes = attributes;
    p.dfu_detach_timeout_ms = 1000;
    return p;
  }
  CountingDetach detach;
  DfuDevice dfu;
  FunctionHost host;
};

TEST(DfuRuntime, DfuUtilDetachesAndTheDeviceLeavesByItself) {
  Application a;
  DfuUtilModel util(a.host, 1, 1024, [](uint32_t) {});
  ASSERT_TRUE(util.detach()) << util.error;
  EXPECT_EQ(util.states, (std::vector<DfuState>{DfuState::kAppIdle}));
  EXPECT_EQ(a.dfu.state(), DfuState::kAppDetach);
  EXPECT_EQ(a.detach.detaches, 0) << "not inside the control transfer";
  a.dfu.poll(0);
  EXPECT_EQ(a.detach.detaches, 1);
  a.dfu.poll(1);
  EXPECT_EQ(a.detach.detaches, 1);
}

TEST(DfuRuntime, WithoutWillDetachTheUsbResetDetaches) {
  Application a(tp::kDfuCanDownload | tp::kDfuManifestationTolerant);
  a.host.out(class_out(static_cast<uint8_t>(DfuRequest::kDetach), 1000, 1, 0), {});
  a.dfu.poll(100);
  EXPECT_EQ(a.detach.detaches, 0);
  a.host.bus_reset();
  a.dfu.poll(200);
  EXPECT_EQ(a.detach.detaches, 1);
}

TEST(DfuRuntime, WithoutWillDetachAndNoResetItReturnsToAppIdle) {
  Application a(tp::kDfuCanDownload | tp::kDfuManifestationTolerant);
  a.host.out(class_out(static_cast<uint8_t>(DfuRequest::kDetach), 1000, 1, 0), {});
  a.dfu.poll(5000);
  a.dfu.poll(5999);
  EXPECT_EQ(a.dfu.state(), DfuState::kAppDetach);
  a.dfu.poll(6001);
  EXPECT_EQ(a.dfu.state(), DfuState::kAppIdle) << "wDetachTimeOut passed";
  a.host.bus_reset();
  a.dfu.poll(7000);
  EXPECT_EQ(a.detach.detaches, 0);
}

TEST(DfuRuntime, AnswersStatusAndStateButNoDownload) {
  Application a;
  EXPECT_EQ(a.host.in(class_in(static_cast<uint8_t>(DfuRequest::kGetStatus), 0, 1, 6)).data,
            (std::vector<uint8_t>{0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(a.host.in(class_in(static_cast<uint8_t>(DfuRequest::kGetState), 0, 1, 1)).data,
            (std::vector<uint8_t>{0}));
  EXPECT_TRUE(a.host.out(class_out(static_cast<uint8_t>(DfuRequest::kDownload), 0, 1, 4), {1, 2, 3, 4}).stalled);
  EXPECT_TRUE(a.host.in(class_in(static_cast<uint8_t>(DfuRequest::kUpload), 0, 1, 64)).stalled);
  EXPECT_EQ(a.dfu.state(), DfuState::kAppIdle) << "run-time refusals change nothing";
}

}  // namespace
}  // namespace tetrapulse::fw::testing
