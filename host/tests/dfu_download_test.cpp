// dfu_download against a scripted DFU 1.1 device model (DFU-mode state machine of the
// DFU 1.1 specification, §6.1 and appendix A): it stalls and goes to dfuERROR on any
// request its state does not allow, including a request sent before bwPollTimeout ran
// out, so a host that does not follow the protocol fails these tests.
#include <gtest/gtest.h>

#include "tetrapulse/host/dfu_download.hpp"

namespace tetrapulse::host {
namespace {

using protocol::DfuState;
using protocol::DfuStatus;
using protocol::DfuStatusCode;
using Bytes = std::vector<uint8_t>;

struct ModelOptions {
  DfuState start = DfuState::kDfuIdle;
  uint32_t busy_polls_per_block = 1;  // GETSTATUS answers dfuDNBUSY this often per block
  uint32_t poll_ms = 5;
  int fail_block = -1;                 // errWRITE when this block is programmed
  DfuStatusCode manifest_verdict = DfuStatusCode::kOk;
  bool manifestation_tolerant = true;
  bool hang = false;  // busy forever
};

class DfuModel final : public DfuControl {
 public:
  explicit DfuModel(ModelOptions o) : o_(o), state_(o.start) {
    if (state_ == DfuState::kDfuError) status_ = DfuStatusCode::kErrUnknown;
  }

  const Bytes& received() const { return received_; }
  const std::vector<uint16_t>& blocks() const { return blocks_; }
  const std::vector<std::string>& log() const { return log_; }
  uint32_t stalls() const { return stalls_; }
  uint64_t waited_ms() const { return waited_; }
  DfuState state() const { return state_; }

 private:
  const std::string& do_name() const override { return name_; }

  HostResult<void> do_download(uint16_t block, protocol::ByteView data) override {
    log_.push_back(data.size == 0 ? "DNLOAD(0)" : "DNLOAD");
    if (!ready()) return stall();
    if (state_ == DfuState::kDfuIdle && data.size > 0) {
      expected_block_ = 0;
    } else if (state_ == DfuState::kDfuDownloadIdle) {
      if (data.size == 0) {
        state_ = DfuState::kDfuManifestSync;
        manifest_done_ = false;
        return {};
      }
    } else {
      return stall();  // DNLOAD(0) in dfuIDLE, or DNLOAD in any other state
    }
    if (block != expected_block_) return stall();
    ++expected_block_;
    received_.insert(received_.end(), data.begin(), data.end());
    blocks_.push_back(block);
    busy_left_ = o_.hang ? UINT32_MAX : o_.busy_polls_per_block;
    failing_ = static_cast<int>(block) == o_.fail_block;
    state_ = DfuState::kDfuDownloadSync;
    return {};
  }

  HostResult<DfuStatus> do_get_status() override {
    log_.push_back("GETSTATUS");
    if (!ready()) return stall();
    DfuStatus s;
    switch (state_) {
      case DfuState::kDfuDownloadSync:
      case DfuState::kDfuDownloadBusy:
        if (busy_left_ > 0) {
          --busy_left_;
          state_ = DfuState::kDfuDownloadBusy;
          busy_until_ = now_ + o_.poll_ms;
          s.poll_timeout_ms = o_.poll_ms;
        } else if (failing_) {
          status_ = DfuStatusCode::kErrWrite;
          state_ = DfuState::kDfuError;
        } else {
          state_ = DfuState::kDfuDownloadIdle;
        }
        break;
      case DfuState::kDfuManifestSync:
        if (!manifest_done_) {
          state_ = DfuState::kDfuManifest;
          busy_until_ = now_ + o_.poll_ms;
          s.poll_timeout_ms = o_.poll_ms;
          manifest_done_ = true;
        } else {
          state_ = DfuState::kDfuIdle;
        }
        break;
      default: break;
    }
    s.status = status_;
    s.state = state_;
    return s;
  }

  HostResult<void> do_clear_status() override {
    log_.push_back("CLRSTATUS");
    if (!ready() || state_ != DfuState::kDfuError) return stall();
    state_ = DfuState::kDfuIdle;
    status_ = DfuStatusCode::kOk;
    return {};
  }

  HostResult<void> do_abort() override {
    log_.push_back("ABORT");
    if (!ready()) return stall();
    if (state_ == DfuState::kDfuIdle || state_ == DfuState::kDfuDownloadIdle || state_ == DfuState::kDfuManifestSync ||
        state_ == DfuState::kDfuUploadIdle) {
      state_ = DfuState::kDfuIdle;
      return {};
    }
    return stall();
  }

  void do_wait_ms(uint32_t ms) override {
    now_ += ms;
    waited_ += ms;
  }

  // Leaves a busy state once its poll timeout has passed; false when the host came too early.
  bool ready() {
    if (state_ == DfuState::kDfuDownloadBusy || state_ == DfuState::kDfuManifest) {
      if (now_ < busy_until_) return false;
      if (state_ == DfuState::kDfuDownloadBusy) state_ = DfuState::kDfuDownloadSync;
      if (state_ == DfuState::kDfuManifest) {
        if (o_.manifest_verdict != DfuStatusCode::kOk) {
          status_ = o_.manifest_verdict;
          state_ = DfuState::kDfuError;
        } else {
          state_ = o_.manifestation_tolerant ? DfuState::kDfuManifestSync : DfuState::kDfuManifestWaitReset;
        }
      }
    }
    return true;
  }

  tl::unexpected<HostError> stall() {
    ++stalls_;
    state_ = DfuState::kDfuError;
    status_ = DfuStatusCode::kErrStalledPacket;
    return host_error(HostErrorKind::kIo, name_, "the device stalled the request");
  }

  ModelOptions o_;
  std::string name_ = "usb:DFU";
  DfuState state_;
  DfuStatusCode status_ = DfuStatusCode::kOk;
  uint64_t now_ = 0, busy_until_ = 0, waited_ = 0;
  uint32_t busy_left_ = 0;
  bool failing_ = false, manifest_done_ = false;
  uint16_t expected_block_ = 0;
  Bytes received_;
  std::vector<uint16_t> blocks_;
  std::vector<std::string> log_;
  uint32_t stalls_ = 0;
};

Bytes image(size_t n) {
  Bytes b(n);
  for (size_t i = 0; i < n; ++i) b[i] = static_cast<uint8_t>(i * 7 + (i >> 8));
  return b;
}

HostResult<DfuDownloadReport> download(DfuModel& m, const Bytes& bytes, DfuDownloadOptions o = {}) {
  return dfu_download(m, protocol::ByteView{bytes.data(), bytes.size()}, o);
}

TEST(DfuDownload, SendsTheImageInTransferSizeBlocksThenManifests) {
  DfuModel m({});
  const Bytes bytes = image(5000);
  std::vector<FlashProgress> progress;
  DfuDownloadOptions o;
  o.progress = [&](const FlashProgress& p) { progress.push_back(p); };
  auto r = download(m, bytes, o);
  ASSERT_TRUE(r) << r.error().what();
  EXPECT_EQ(m.received(), bytes);
  EXPECT_EQ(m.blocks(), (std::vector<uint16_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(r->blocks, 5u);
  EXPECT_FALSE(r->needs_reset);
  EXPECT_EQ(m.stalls(), 0u);
  EXPECT_EQ(m.state(), DfuState::kDfuIdle);
  EXPECT_EQ(m.log()[m.log().size() - 3], "DNLOAD(0)");
  ASSERT_FALSE(progress.empty());
  EXPECT_EQ(progress.back().stage, std::string("manifest"));
  EXPECT_EQ(progress[4].done, 5000u);
}

TEST(DfuDownload, WaitsOutEveryPollTimeoutOfABusyDevice) {
  ModelOptions o;
  o.busy_polls_per_block = 3;
  o.poll_ms = 25;
  DfuModel m(o);
  const Bytes bytes = image(3 * 1024);
  DfuDownloadOptions small;
  small.transfer_size = 1024;
  auto r = download(m, bytes, small);
  ASSERT_TRUE(r) << r.error().what();
  EXPECT_EQ(m.stalls(), 0u) << "no request came before bwPollTimeout ran out";
  EXPECT_EQ(m.received(), bytes);
  EXPECT_GE(m.waited_ms(), 3u * 3u * 25u + 25u);  // every busy answer, and manifestation
}

TEST(DfuDownload, ClearsAnErrorAndAbortsAnUnfinishedTransferFirst) {
  for (DfuState start : {DfuState::kDfuError, DfuState::kDfuDownloadIdle}) {
    ModelOptions o;
    o.start = start;
    DfuModel m(o);
    auto r = download(m, image(100));
    ASSERT_TRUE(r) << r.error().what();
    EXPECT_EQ(m.log()[1], start == DfuState::kDfuError ? "CLRSTATUS" : "ABORT");
    EXPECT_EQ(m.stalls(), 0u);
  }
}

TEST(DfuDownload, AWriteErrorNamesTheBlockAndLeavesTheDeviceClear) {
  ModelOptions o;
  o.fail_block = 2;
  DfuModel m(o);
  auto r = download(m, image(5000));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kBoardRefused);
  EXPECT_EQ(r.error().protocol_error, protocol::Error::kFlashError);
  EXPECT_EQ(r.error().what(), "usb:DFU: block 2 (bytes 2048..3072): the device reports errWRITE in dfuERROR");
  EXPECT_EQ(m.state(), DfuState::kDfuIdle);
}

TEST(DfuDownload, AFailedManifestationIsAnError) {
  ModelOptions o;
  o.manifest_verdict = DfuStatusCode::kErrVerify;
  DfuModel m(o);
  auto r = download(m, image(300));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().protocol_error, protocol::Error::kImageRejected);
  EXPECT_EQ(r.error().what(), "usb:DFU: manifestation: the device reports errVERIFY in dfuERROR");
}

TEST(DfuDownload, ADeviceThatIsNotManifestationTolerantWantsAReset) {
  ModelOptions o;
  o.manifestation_tolerant = false;
  DfuModel m(o);
  auto r = download(m, image(300));
  ASSERT_TRUE(r) << r.error().what();
  EXPECT_TRUE(r->needs_reset);
  EXPECT_EQ(m.state(), DfuState::kDfuManifestWaitReset);
}

TEST(DfuDownload, CancellingAbortsBetweenBlocks) {
  DfuModel m({});
  CancelFlag cancel{false};
  DfuDownloadOptions o;
  o.cancel = &cancel;
  o.progress = [&](const FlashProgress& p) { cancel = p.done >= 2048; };
  auto r = download(m, image(5000), o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kCancelled);
  EXPECT_EQ(m.log().back(), "ABORT");
  EXPECT_EQ(m.state(), DfuState::kDfuIdle);
  EXPECT_EQ(m.blocks().size(), 2u);
}

TEST(DfuDownload, AHungDeviceTimesOut) {
  ModelOptions o;
  o.hang = true;
  DfuModel m(o);
  DfuDownloadOptions limited;
  limited.max_polls = 20;
  auto r = download(m, image(10), limited);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kTimeout);
  EXPECT_EQ(m.stalls(), 0u);
}

}  // namespace
}  // namespace tetrapulse::host
