#include "tetrapulse/host/usb_link.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "usb_device.hpp"

namespace tetrapulse::host {
namespace {

int milliseconds_up(int64_t ns) { return static_cast<int>(std::max<int64_t>(1, (ns + 999'999) / 1'000'000)); }

// The bulk endpoints of a real board through libusb, reopened by serial number when the
// board re-enumerates.
class LibusbBulkPipe final : public UsbBulkPipe {
 public:
  LibusbBulkPipe(std::string name, std::string serial, std::unique_ptr<usb::UsbBoardHandle> board,
                 UsbLinkOptions options)
      : name_(std::move(name)), serial_(std::move(serial)), board_(std::move(board)), options_(options) {}

 private:
  std::optional<protocol::UsbProtocolInfo> do_protocol_info() const override {
    return board_ ? board_->listing().protocol_info : std::nullopt;
  }

  HostResult<void> do_write_transfer(protocol::ByteView transfer, int timeout_ms) override {
    for (int attempt = 0;; ++attempt) {
      if (auto ready = reconnect(static_cast<int>(options_.reconnect_timeout.count())); !ready) return ready;
      const UsbMessageInterface& m = *board_->layout().messages;
      int r = bulk(m.bulk_out, const_cast<uint8_t*>(transfer.data), static_cast<int>(transfer.size), timeout_ms);
      if (r == 0 && transfer.size % m.out_packet_size == 0) r = bulk(m.bulk_out, nullptr, 0, timeout_ms);
      if (r == 0) return {};
      if (r == LIBUSB_ERROR_NO_DEVICE && attempt == 0) {
        board_.reset();  // re-enumerating: reopen and send once more
        continue;
      }
      if (r == LIBUSB_ERROR_TIMEOUT) {
        return host_error(HostErrorKind::kTimeout, name_, "bulk OUT: the board takes no data", protocol::Error::kTimeout);
      }
      if (r == LIBUSB_ERROR_PIPE) libusb_clear_halt(board_->get(), m.bulk_out);
      return host_error(HostErrorKind::kIo, name_, "bulk OUT: " + usb::describe(r));
    }
  }

  HostResult<std::optional<std::vector<uint8_t>>> do_read_transfer(int timeout_ms) override {
    if (auto ready = reconnect(timeout_ms); !ready) return tl::unexpected(ready.error());
    const UsbMessageInterface& m = *board_->layout().messages;
    // A whole number of packets no smaller than the largest transfer (SPEC.md §5.4).
    const size_t packet = std::max<size_t>(m.in_packet_size, 1);
    std::vector<uint8_t> buffer((protocol::kUsbBulkReadSize + packet - 1) / packet * packet);
    int got = 0;
    const int r = libusb_bulk_transfer(board_->get(), m.bulk_in, buffer.data(), static_cast<int>(buffer.size()), &got,
                                       static_cast<unsigned>(timeout_ms));
    if (r == 0) {
      buffer.resize(static_cast<size_t>(got));
      return buffer;
    }
    if (r == LIBUSB_ERROR_TIMEOUT || r == LIBUSB_ERROR_OVERFLOW) {
      if (got == 0 && r == LIBUSB_ERROR_TIMEOUT) return std::nullopt;
      // Cut short or too long: handed on as it came, and the framing refuses it.
      buffer.resize(r == LIBUSB_ERROR_OVERFLOW ? buffer.size() : static_cast<size_t>(got));
      return buffer;
    }
    if (r == LIBUSB_ERROR_NO_DEVICE) {
      board_.reset();
      return std::nullopt;  // the next call waits for the board to come back
    }
    if (r == LIBUSB_ERROR_PIPE) {
      libusb_clear_halt(board_->get(), m.bulk_in);
      return std::nullopt;
    }
    return host_error(HostErrorKind::kIo, name_, "bulk IN: " + usb::describe(r));
  }

  int bulk(uint8_t endpoint, uint8_t* data, int size, int timeout_ms) {
    int done = 0;
    const int r = libusb_bulk_transfer(board_->get(), endpoint, data, size, &done, static_cast<unsigned>(timeout_ms));
    return r == 0 && done != size ? LIBUSB_ERROR_IO : r;
  }

  HostResult<void> reconnect(int timeout_ms) {
    if (board_) return {};
    auto board = usb::wait_for_board(serial_, protocol::UsbMode::kApplication, timeout_ms);
    if (!board) {
      HostError e = board.error();
      e.device = name_;
      e.message = "went away: " + e.message;
      return tl::unexpected(e);
    }
    if (auto claimed = (*board)->claim((*board)->layout().messages->number, name_); !claimed) return claimed;
    board_ = std::move(*board);
    return {};
  }

  std::string name_;
  std::string serial_;
  std::unique_ptr<usb::UsbBoardHandle> board_;
  UsbLinkOptions options_;
};

}  // namespace

namespace {

HostResult<std::unique_ptr<UsbLink>> link_to(HostResult<std::unique_ptr<usb::UsbBoardHandle>> board,
                                            UsbLinkOptions options) {
  if (!board) return tl::unexpected(board.error());
  const std::string name = usb_link_name((*board)->listing().serial);
  if (auto claimed = (*board)->claim((*board)->layout().messages->number, name); !claimed) {
    return tl::unexpected(claimed.error());
  }
  // Reconnect by the serial the board has, even when it was opened as "the only one".
  const std::string board_serial = (*board)->listing().serial;
  return std::make_unique<UsbLink>(name, std::make_unique<LibusbBulkPipe>(name, board_serial, std::move(*board), options));
}

}  // namespace

HostResult<std::unique_ptr<UsbLink>> UsbLink::open(const std::string& serial, UsbLinkOptions options) {
  return link_to(usb::open_board(serial, protocol::UsbMode::kApplication), options);
}

HostResult<std::unique_ptr<UsbLink>> UsbLink::wait_and_open(const std::string& serial, std::chrono::milliseconds timeout,
                                                            UsbLinkOptions options) {
  return link_to(usb::wait_for_board(serial, protocol::UsbMode::kApplication, static_cast<int>(timeout.count())), options);
}

HostResult<void> UsbLink::send_bytes(protocol::ByteView message) {
  uint8_t transfer[protocol::kUsbBulkMaxTransfer];
  const protocol::Result<size_t> size = protocol::encode_usb_bulk_frame(message, transfer, sizeof(transfer));
  if (!size) {
    return host_error(HostErrorKind::kBadInput, name(),
                      fmt::format("cannot frame a {}-byte message: {}", message.size, protocol::error_name(size.error())),
                      size.error());
  }
  return pipe_->write_transfer(protocol::ByteView{transfer, *size}, static_cast<int>(kDefaultTimeout.count()));
}

HostResult<std::optional<RawMessage>> UsbLink::receive_bytes(int64_t timeout_ns) {
  const int64_t deadline = monotonic_now_ns() + timeout_ns;
  for (;;) {
    const int64_t left = deadline - monotonic_now_ns();
    if (left <= 0) return std::nullopt;
    auto transfer = pipe_->read_transfer(milliseconds_up(left));
    if (!transfer) return tl::unexpected(transfer.error());
    if (!transfer->has_value()) continue;
    const std::vector<uint8_t>& t = **transfer;
    if (t.empty()) continue;  // a lone ZLP is ignored (SPEC.md §5.4)
    const protocol::Result<protocol::ByteView> message = protocol::decode_usb_bulk_frame(protocol::ByteView{t.data(), t.size()});
    if (!message) {
      ++counters_.transport_errors;
      continue;
    }
    return RawMessage{std::vector<uint8_t>(message->begin(), message->end()), monotonic_now_ns(), 0};
  }
}

}  // namespace tetrapulse::host
