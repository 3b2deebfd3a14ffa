#include "dfu_util_model.hpp"

namespace tetrapulse::fw::testing {

namespace tp = protocol;
using tp::DfuRequest;
using tp::DfuState;
using tp::DfuStatusCode;

namespace {
uint8_t code(DfuRequest r) { return static_cast<uint8_t>(r); }
}  // namespace

bool DfuUtilModel::fail(const std::string& what) {
  error = what;
  return false;
}

void DfuUtilModel::sleep(uint32_t ms) {
  slept_ms += ms;
  sleep_(ms);
}

std::optional<tp::DfuStatus> DfuUtilModel::get_status() {
  const ControlResult r = pipe_.in(class_in(code(DfuRequest::kGetStatus), 0, interface_, tp::kDfuStatusSize));
  if (r.stalled) return std::nullopt;
  const tp::Result<tp::DfuStatus> s = tp::decode_dfu_status(tp::ByteView{r.data.data(), r.data.size()});
  if (!s) return std::nullopt;
  last = *s;
  states.push_back(s->state);
  return *s;
}

bool DfuUtilModel::detach() {
  const std::optional<tp::DfuStatus> s = get_status();
  const DfuState state = s ? s->state : DfuState::kAppIdle;  // "does not implement get_status, assuming appIDLE"
  if (state != DfuState::kAppIdle && state != DfuState::kAppDetach) return fail("not in run-time mode");
  if (pipe_.out(class_out(code(DfuRequest::kDetach), 1000, interface_, 0), {}).stalled) return fail("error detaching");
  return true;
}

bool DfuUtilModel::start_session() {
  std::optional<tp::DfuStatus> s;
  for (int again = 0; again < 8; ++again) {  // dfu-util's "status_again" loop
    s = get_status();
    if (!s) return fail("error get_status");
    sleep(s->poll_timeout_ms);
    if (s->state == DfuState::kAppIdle || s->state == DfuState::kAppDetach) {
      return fail("Device still in Run-Time Mode!");
    }
    if (s->state == DfuState::kDfuError) {
      if (pipe_.out(class_out(code(DfuRequest::kClearStatus), 0, interface_, 0), {}).stalled) {
        return fail("error clear_status");
      }
      continue;
    }
    if (s->state == DfuState::kDfuDownloadIdle || s->state == DfuState::kDfuUploadIdle) {
      if (pipe_.out(class_out(code(DfuRequest::kAbort), 0, interface_, 0), {}).stalled) {
        return fail("can't send DFU_ABORT");
      }
      continue;
    }
    break;
  }
  if (s->status != DfuStatusCode::kOk) {
    if (pipe_.out(class_out(code(DfuRequest::kClearStatus), 0, interface_, 0), {}).stalled) {
      return fail("USB communication error");
    }
    s = get_status();
    if (!s || s->status != DfuStatusCode::kOk) return fail("Status is not OK");
    sleep(s->poll_timeout_ms);
  }
  return true;
}

bool DfuUtilModel::download(const std::vector<uint8_t>& file) {
  if (!start_session()) return false;
  uint16_t transaction = 0;
  for (size_t sent = 0; sent < file.size();) {
    const size_t n = std::min<size_t>(transfer_size_, file.size() - sent);
    const std::vector<uint8_t> block(file.begin() + static_cast<std::ptrdiff_t>(sent),
                                     file.begin() + static_cast<std::ptrdiff_t>(sent + n));
    block_numbers.push_back(transaction);
    if (pipe_.out(class_out(code(DfuRequest::kDownload), transaction++, interface_, static_cast<uint16_t>(n)), block)
            .stalled) {
      return fail("Error during download");
    }
    sent += n;
    for (;;) {
      const std::optional<tp::DfuStatus> s = get_status();
      if (!s) return fail("Error during download get_status");
      if (s->state == DfuState::kDfuDownloadIdle || s->state == DfuState::kDfuError) break;
      sleep(s->poll_timeout_ms);  // "Wait while device executes flashing"
    }
    if (last.status != DfuStatusCode::kOk) return fail("download failed");
  }
  block_numbers.push_back(transaction);
  if (pipe_.out(class_out(code(DfuRequest::kDownload), transaction, interface_, 0), {}).stalled) {
    return fail("Error sending completion packet");
  }
  for (;;) {  // "Transition to MANIFEST_SYNC state"
    const std::optional<tp::DfuStatus> s = get_status();
    if (!s) return fail("unable to read DFU status after completion");
    sleep(s->poll_timeout_ms);
    if (s->state == DfuState::kDfuManifestSync || s->state == DfuState::kDfuManifest) {
      sleep(1000);
      continue;
    }
    if (s->state == DfuState::kDfuManifestWaitReset) pipe_.bus_reset();  // "Resetting USB"
    break;
  }
  if (last.state == DfuState::kDfuError || last.status != DfuStatusCode::kOk) return fail("manifestation failed");
  return true;
}

std::optional<std::vector<uint8_t>> DfuUtilModel::upload() {
  if (!start_session()) return std::nullopt;
  std::vector<uint8_t> file;
  uint16_t transaction = 0;
  for (;;) {
    const ControlResult r = pipe_.in(class_in(code(DfuRequest::kUpload), transaction++, interface_, transfer_size_));
    if (r.stalled) {
      fail("Error during upload");
      return std::nullopt;
    }
    file.insert(file.end(), r.data.begin(), r.data.end());
    if (r.data.size() < transfer_size_) return file;
  }
}

}  // namespace tetrapulse::fw::testing
