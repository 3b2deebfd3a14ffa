#include "tetrapulse/fw/usb/dfu_device.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;
using tp::DfuRequest;
using tp::DfuState;
using tp::DfuStatusCode;

DfuDevice::DfuDevice(DfuRuntimeTarget& target, const tp::UsbDeviceParams& params)
    : runtime_(&target),
      attributes_(params.dfu_attributes),
      detach_timeout_ms_(params.dfu_detach_timeout_ms),
      transfer_size_(params.dfu_transfer_size),
      state_(DfuState::kAppIdle) {}

DfuDevice::DfuDevice(DfuDownloadTarget& target, const tp::UsbDeviceParams& params, uint8_t* block, size_t capacity)
    : target_(&target),
      attributes_(params.dfu_attributes),
      detach_timeout_ms_(params.dfu_detach_timeout_ms),
      transfer_size_(params.dfu_transfer_size),
      block_(block),
      capacity_(capacity),
      state_(DfuState::kDfuIdle) {}

bool DfuDevice::downloading() const {
  return state_ == DfuState::kDfuDownloadSync || state_ == DfuState::kDfuDownloadBusy ||
         state_ == DfuState::kDfuDownloadIdle || state_ == DfuState::kDfuManifestSync ||
         state_ == DfuState::kDfuManifest;
}

void DfuDevice::end_transfer() {
  if (downloading()) target_->abort();
  state_ = DfuState::kDfuIdle;
  scheduled_ = ready_ = Work::kNone;
  offset_ = 0;
  block_size_ = 0;
  block_written_ = manifested_ = verdict_pending_ = false;
}

void DfuDevice::fail(DfuStatusCode status) {
  end_transfer();
  state_ = DfuState::kDfuError;
  status_ = status;
}

UsbControlReply DfuDevice::refuse() {
  if (target_ != nullptr && state_ != DfuState::kDfuError && state_ != DfuState::kDfuManifestWaitReset) {
    fail(DfuStatusCode::kErrStalledPacket);
  }
  return UsbControlReply::stall();
}

UsbControlReply DfuDevice::do_setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
  scheduled_ = Work::kNone;
  verdict_pending_ = false;
  if (setup.type() != UsbRequestType::kClass) return refuse();
  if (runtime_ != nullptr) return runtime_request(setup, scratch, capacity);

  const bool in = setup.device_to_host();
  if (state_ == DfuState::kDfuManifestWaitReset) {
    // Waiting for the reset: the status still answers (dfu-util then resets the bus).
    if (in && static_cast<DfuRequest>(setup.request) == DfuRequest::kGetStatus) return get_status(scratch, capacity);
    return UsbControlReply::stall();
  }
  if (state_ == DfuState::kDfuDownloadBusy || state_ == DfuState::kDfuManifest) return refuse();
  switch (static_cast<DfuRequest>(setup.request)) {
    case DfuRequest::kGetStatus:
    case DfuRequest::kGetState:
      return state_request(setup, scratch, capacity);
    case DfuRequest::kDownload:
      if (in) break;
      return download(setup);
    case DfuRequest::kUpload:
      if (!in) break;
      return upload(setup, scratch, capacity);
    case DfuRequest::kClearStatus:
      if (in || setup.length != 0 || state_ != DfuState::kDfuError) break;
      state_ = DfuState::kDfuIdle;
      status_ = DfuStatusCode::kOk;
      return UsbControlReply::accept();
    case DfuRequest::kAbort:
      if (in || setup.length != 0) break;
      if (state_ != DfuState::kDfuIdle && state_ != DfuState::kDfuDownloadIdle && state_ != DfuState::kDfuUploadIdle) {
        break;
      }
      end_transfer();
      return UsbControlReply::accept();
    case DfuRequest::kDetach:
      break;  // DFU mode has nothing to detach from
  }
  return refuse();
}

// GETSTATUS and GETSTATE, alike in both modes.
UsbControlReply DfuDevice::state_request(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
  if (!setup.device_to_host()) return refuse();
  if (static_cast<DfuRequest>(setup.request) == DfuRequest::kGetStatus) return get_status(scratch, capacity);
  if (setup.length < 1 || capacity < 1) return refuse();
  scratch[0] = static_cast<uint8_t>(state_);
  return UsbControlReply::send(scratch, 1);
}

UsbControlReply DfuDevice::runtime_request(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
  const bool in = setup.device_to_host();
  switch (static_cast<DfuRequest>(setup.request)) {
    case DfuRequest::kGetStatus:
    case DfuRequest::kGetState:
      return state_request(setup, scratch, capacity);  // refused: a stall (no target here)
    case DfuRequest::kDetach:
      if (in || setup.length != 0) break;
      state_ = DfuState::kAppDetach;
      detach_clock_started_ = false;
      if ((attributes_ & tp::kDfuWillDetach) != 0) {
        scheduled_ = Work::kDetach;
      } else {
        detach_armed_ = true;  // the host resets the bus within wDetachTimeOut
      }
      return UsbControlReply::accept();
    default:
      break;
  }
  return UsbControlReply::stall();  // run-time requests never change the state when refused
}

UsbControlReply DfuDevice::get_status(uint8_t* scratch, size_t capacity) {
  uint32_t poll_ms = 0;
  switch (state_) {
    case DfuState::kDfuDownloadSync:
      if (block_written_) {
        state_ = DfuState::kDfuDownloadIdle;
      } else {
        state_ = DfuState::kDfuDownloadBusy;
        poll_ms = target_->download_poll_ms(offset_, block_size_);
        scheduled_ = Work::kWrite;
      }
      break;
    case DfuState::kDfuManifestSync:
      if (manifested_) {
        state_ = DfuState::kDfuIdle;  // bitManifestationTolerant: the verdict is OK
        manifested_ = false;
        offset_ = 0;
        verdict_pending_ = true;
      } else {
        state_ = DfuState::kDfuManifest;
        poll_ms = target_->manifest_poll_ms();
        scheduled_ = Work::kManifest;
      }
      break;
    default:
      break;
  }
  tp::DfuStatus answer;
  answer.status = status_;
  answer.poll_timeout_ms = poll_ms < tp::kDfuMaxPollTimeoutMs ? poll_ms : tp::kDfuMaxPollTimeoutMs;
  answer.state = state_;
  const tp::Result<size_t> n = tp::encode_dfu_status(answer, scratch, capacity);
  if (!n) return UsbControlReply::stall();
  return UsbControlReply::send(scratch, *n);
}

UsbControlReply DfuDevice::download(const UsbSetup& setup) {
  if ((attributes_ & tp::kDfuCanDownload) == 0) return refuse();
  if (state_ != DfuState::kDfuIdle && state_ != DfuState::kDfuDownloadIdle) return refuse();
  if (setup.length == 0) {
    if (state_ != DfuState::kDfuDownloadIdle) return refuse();  // nothing was downloaded
    state_ = DfuState::kDfuManifestSync;
    manifested_ = false;
    return UsbControlReply::accept();
  }
  if (setup.length > transfer_size_ || setup.length > capacity_) return refuse();
  if (state_ == DfuState::kDfuIdle) offset_ = 0;  // a new download
  return UsbControlReply::receive(block_, capacity_);
}

bool DfuDevice::do_data_out(const UsbSetup& setup, tp::ByteView data) {
  if (target_ == nullptr || static_cast<DfuRequest>(setup.request) != DfuRequest::kDownload ||
      data.size != setup.length) {
    refuse();
    return false;
  }
  block_size_ = data.size;
  block_written_ = false;
  state_ = DfuState::kDfuDownloadSync;
  return true;
}

UsbControlReply DfuDevice::upload(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
  if ((attributes_ & tp::kDfuCanUpload) == 0) return refuse();
  if (state_ != DfuState::kDfuIdle && state_ != DfuState::kDfuUploadIdle) return refuse();
  if (state_ == DfuState::kDfuIdle) offset_ = 0;
  size_t want = setup.length < capacity ? setup.length : capacity;
  if (want > transfer_size_) want = transfer_size_;
  const tp::Result<size_t> n = target_->upload(offset_, scratch, want);
  if (!n || *n > want) return refuse();
  offset_ += static_cast<uint32_t>(*n);
  // A block shorter than wLength is the last one.
  if (*n < setup.length) {
    state_ = DfuState::kDfuIdle;
    offset_ = 0;
  } else {
    state_ = DfuState::kDfuUploadIdle;
  }
  return UsbControlReply::send(scratch, *n);
}

void DfuDevice::do_status_complete(const UsbSetup&) {
  ready_ = scheduled_;
  scheduled_ = Work::kNone;
  if (verdict_pending_) {
    installed_ = true;
    verdict_pending_ = false;
  }
}

void DfuDevice::do_bus_reset() {
  scheduled_ = ready_ = Work::kNone;
  if (runtime_ != nullptr) {
    if (state_ == DfuState::kAppDetach && detach_armed_) ready_ = Work::kDetach;
    return;
  }
  if (state_ == DfuState::kDfuManifestWaitReset) {
    installed_ = true;
    return;
  }
  if (downloading() || state_ == DfuState::kDfuUploadIdle) end_transfer();
}

void DfuDevice::poll(uint32_t now_ms) {
  const Work work = ready_;
  ready_ = Work::kNone;
  switch (work) {
    case Work::kWrite: {
      if (state_ != DfuState::kDfuDownloadBusy) break;
      const DfuStatusCode s = target_->download(offset_, tp::ByteView{block_, block_size_});
      if (s != DfuStatusCode::kOk) {
        fail(s);
        break;
      }
      offset_ += static_cast<uint32_t>(block_size_);
      block_written_ = true;
      state_ = DfuState::kDfuDownloadSync;
      break;
    }
    case Work::kManifest: {
      if (state_ != DfuState::kDfuManifest) break;
      const DfuStatusCode s = target_->manifest(offset_);
      if (s != DfuStatusCode::kOk) {
        fail(s);
        break;
      }
      if ((attributes_ & tp::kDfuManifestationTolerant) != 0) {
        manifested_ = true;
        state_ = DfuState::kDfuManifestSync;
      } else {
        state_ = DfuState::kDfuManifestWaitReset;
      }
      break;
    }
    case Work::kDetach:
      detach_armed_ = false;
      runtime_->detach();
      break;
    case Work::kNone:
      break;
  }
  // Run-time without bitWillDetach: no USB reset within wDetachTimeOut, back to appIDLE.
  if (detach_armed_) {
    if (!detach_clock_started_) {
      detach_clock_started_ = true;
      detach_since_ms_ = now_ms;
    } else if (now_ms - detach_since_ms_ > detach_timeout_ms_) {
      detach_armed_ = false;
      state_ = DfuState::kAppIdle;
    }
  }
}

}  // namespace tetrapulse::fw
