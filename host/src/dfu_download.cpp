#include "tetrapulse/host/dfu_download.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace tetrapulse::host {

using protocol::DfuState;
using protocol::DfuStatus;
using protocol::DfuStatusCode;

const char* dfu_state_name(DfuState state) {
  switch (state) {
    case DfuState::kAppIdle: return "appIDLE";
    case DfuState::kAppDetach: return "appDETACH";
    case DfuState::kDfuIdle: return "dfuIDLE";
    case DfuState::kDfuDownloadSync: return "dfuDNLOAD-SYNC";
    case DfuState::kDfuDownloadBusy: return "dfuDNBUSY";
    case DfuState::kDfuDownloadIdle: return "dfuDNLOAD-IDLE";
    case DfuState::kDfuManifestSync: return "dfuMANIFEST-SYNC";
    case DfuState::kDfuManifest: return "dfuMANIFEST";
    case DfuState::kDfuManifestWaitReset: return "dfuMANIFEST-WAIT-RESET";
    case DfuState::kDfuUploadIdle: return "dfuUPLOAD-IDLE";
    case DfuState::kDfuError: return "dfuERROR";
  }
  return "unknown";
}

const char* dfu_status_name(DfuStatusCode status) {
  static const char* const kNames[] = {"OK",        "errTARGET",   "errFILE",  "errWRITE",   "errERASE",
                                       "errCHECK_ERASED", "errPROG", "errVERIFY", "errADDRESS", "errNOTDONE",
                                       "errFIRMWARE", "errVENDOR", "errUSBR",  "errPOR",     "errUNKNOWN",
                                       "errSTALLEDPKT"};
  const auto i = static_cast<size_t>(status);
  return i < sizeof(kNames) / sizeof(kNames[0]) ? kNames[i] : "unknown";
}

namespace {

protocol::Error protocol_error_of(DfuStatusCode s) {
  switch (s) {
    case DfuStatusCode::kErrTarget:
    case DfuStatusCode::kErrFile:
    case DfuStatusCode::kErrVerify:
    case DfuStatusCode::kErrFirmware: return protocol::Error::kImageRejected;
    case DfuStatusCode::kErrWrite:
    case DfuStatusCode::kErrErase:
    case DfuStatusCode::kErrCheckErased:
    case DfuStatusCode::kErrProg: return protocol::Error::kFlashError;
    default: return protocol::Error::kNone;
  }
}

class Download {
 public:
  Download(DfuControl& device, protocol::ByteView image, const DfuDownloadOptions& options)
      : device_(device), image_(image), options_(options) {}

  HostResult<DfuDownloadReport> run() {
    if (options_.transfer_size == 0 || options_.transfer_size > 0xFFFF) {
      return fail(HostErrorKind::kBadInput, fmt::format("transfer size {} is not 1..65535", options_.transfer_size));
    }
    if (auto idle = to_idle(); !idle) return tl::unexpected(idle.error());
    uint32_t block = 0;
    for (size_t at = 0; at < image_.size; ++block) {
      if (options_.cancel != nullptr && options_.cancel->load()) {
        device_.abort();
        return fail(HostErrorKind::kCancelled, "download cancelled");
      }
      const size_t n = std::min(options_.transfer_size, image_.size - at);
      const std::string what = fmt::format("block {} (bytes {}..{})", block, at, at + n);
      if (auto sent = device_.download(static_cast<uint16_t>(block), image_.subview(at, n)); !sent) {
        return tl::unexpected(prefixed(sent.error(), what));
      }
      auto status = poll_until(what, [](DfuState s) { return s == DfuState::kDfuDownloadIdle; });
      if (!status) return tl::unexpected(status.error());
      at += n;
      ++report_.blocks;
      if (options_.progress) options_.progress(FlashProgress{"download", at, image_.size});
    }
    // The zero-length DNLOAD: end of image, manifestation starts.
    if (auto sent = device_.download(static_cast<uint16_t>(block), protocol::ByteView{}); !sent) {
      return tl::unexpected(prefixed(sent.error(), "end of download"));
    }
    if (options_.progress) options_.progress(FlashProgress{"manifest", 0, 1});
    auto status = poll_until("manifestation", [](DfuState s) {
      return s == DfuState::kDfuIdle || s == DfuState::kDfuManifestWaitReset;
    });
    if (!status) return tl::unexpected(status.error());
    report_.needs_reset = status->state == DfuState::kDfuManifestWaitReset;
    if (options_.progress) options_.progress(FlashProgress{"manifest", 1, 1});
    return report_;
  }

 private:
  tl::unexpected<HostError> fail(HostErrorKind kind, std::string message,
                                 protocol::Error error = protocol::Error::kNone) const {
    return host_error(kind, device_.name(), std::move(message), error);
  }

  static HostError prefixed(HostError e, const std::string& what) {
    e.message = what + ": " + e.message;
    return e;
  }

  // Brings the device to dfuIDLE: clears an error, aborts a transfer in progress.
  HostResult<void> to_idle() {
    auto status = device_.get_status();
    if (!status) return tl::unexpected(prefixed(status.error(), "DFU_GETSTATUS"));
    if (status->state == DfuState::kDfuError) {
      if (auto cleared = device_.clear_status(); !cleared) return tl::unexpected(prefixed(cleared.error(), "DFU_CLRSTATUS"));
    } else if (status->state == DfuState::kDfuDownloadIdle || status->state == DfuState::kDfuUploadIdle ||
               status->state == DfuState::kDfuManifestSync) {
      if (auto aborted = device_.abort(); !aborted) return tl::unexpected(prefixed(aborted.error(), "DFU_ABORT"));
    } else if (status->state == DfuState::kDfuIdle) {
      return {};
    }
    status = device_.get_status();
    if (!status) return tl::unexpected(prefixed(status.error(), "DFU_GETSTATUS"));
    if (status->state != DfuState::kDfuIdle) {
      return fail(HostErrorKind::kMalformed,
                  fmt::format("not ready for a download: {} ({}); is it in DFU mode?", dfu_state_name(status->state),
                              dfu_status_name(status->status)));
    }
    return {};
  }

  // GETSTATUS until `done(state)`, waiting bwPollTimeout while the device is busy.
  template <class Done>
  HostResult<DfuStatus> poll_until(const std::string& what, Done done) {
    for (uint32_t polls = 0; polls < options_.max_polls; ++polls) {
      auto status = device_.get_status();
      ++report_.polls;
      if (!status) return tl::unexpected(prefixed(status.error(), what + ": DFU_GETSTATUS"));
      if (status->status != DfuStatusCode::kOk || status->state == DfuState::kDfuError) {
        device_.clear_status();  // leaves the device ready for another attempt
        return fail(HostErrorKind::kBoardRefused,
                    fmt::format("{}: the device reports {} in {}", what, dfu_status_name(status->status),
                                dfu_state_name(status->state)),
                    protocol_error_of(status->status));
      }
      if (done(status->state)) return *status;
      const bool busy = status->state == DfuState::kDfuDownloadBusy || status->state == DfuState::kDfuDownloadSync ||
                        status->state == DfuState::kDfuManifest || status->state == DfuState::kDfuManifestSync;
      if (!busy) {
        return fail(HostErrorKind::kMalformed, fmt::format("{}: unexpected state {}", what, dfu_state_name(status->state)));
      }
      device_.wait_ms(status->poll_timeout_ms);
    }
    return fail(HostErrorKind::kTimeout, fmt::format("{}: still busy after {} polls", what, options_.max_polls),
                protocol::Error::kTimeout);
  }

  DfuControl& device_;
  protocol::ByteView image_;
  const DfuDownloadOptions& options_;
  DfuDownloadReport report_;
};

}  // namespace

HostResult<DfuDownloadReport> dfu_download(DfuControl& device, protocol::ByteView image,
                                           const DfuDownloadOptions& options) {
  return Download(device, image, options).run();
}

}  // namespace tetrapulse::host
