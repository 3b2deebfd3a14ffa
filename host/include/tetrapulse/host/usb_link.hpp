#pragma once
// A board on USB (protocol/SPEC.md §5): one message per bulk transfer, framed as
// [length u16][message], on the bulk endpoints of interface FF/54/01 whose addresses come
// from the configuration descriptor. Opening checks the product string and the
// PROTOCOL_INFO handshake (the PIDs are shared test PIDs). When the board goes away
// (reset, replugged, re-enumerated) the link waits for the board with the same serial
// number to come back, reopens it and carries on.
// Receive timestamps are when the bulk IN transfer completed (CLOCK_MONOTONIC).
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/host/link.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::host {

// The bulk endpoints as UsbLink uses them; libusb on a real board, a fake in tests.
class UsbBulkPipe {
 public:
  virtual ~UsbBulkPipe() = default;  // owned through the base (unique_ptr<UsbBulkPipe>)
  // One bulk OUT transfer; a transfer whose size is a multiple of the endpoint's packet
  // size is followed by a zero-length packet (SPEC.md §5.4).
  HostResult<void> write_transfer(protocol::ByteView transfer, int timeout_ms) {
    return do_write_transfer(transfer, timeout_ms);
  }
  // One bulk IN transfer; nullopt when none completed within `timeout_ms`. A transfer cut
  // short or overflowing comes as it arrived (the framing then refuses it).
  HostResult<std::optional<std::vector<uint8_t>>> read_transfer(int timeout_ms) { return do_read_transfer(timeout_ms); }
  // The board's PROTOCOL_INFO answer when it was (last) opened, if the pipe has one.
  std::optional<protocol::UsbProtocolInfo> protocol_info() const { return do_protocol_info(); }

 private:
  virtual HostResult<void> do_write_transfer(protocol::ByteView transfer, int timeout_ms) = 0;
  virtual HostResult<std::optional<std::vector<uint8_t>>> do_read_transfer(int timeout_ms) = 0;
  virtual std::optional<protocol::UsbProtocolInfo> do_protocol_info() const { return std::nullopt; }
};

struct UsbLinkOptions {
  // How long a link waits for its board to come back after it went away.
  std::chrono::milliseconds reconnect_timeout{5000};
};

class UsbLink : public Link {
 public:
  // The application-mode board with this serial number ("" = the only one).
  static HostResult<std::unique_ptr<UsbLink>> open(const std::string& serial, UsbLinkOptions options = {});
  // open(), waiting up to `timeout` for the board to appear (after a reset or a flash).
  static HostResult<std::unique_ptr<UsbLink>> wait_and_open(const std::string& serial, std::chrono::milliseconds timeout,
                                                            UsbLinkOptions options = {});
  UsbLink(std::string name, std::unique_ptr<UsbBulkPipe> pipe) : Link(std::move(name)), pipe_(std::move(pipe)) {}

  // The board's USB serial number ("" over a fake pipe).
  std::string serial() const { return name().rfind("usb:", 0) == 0 ? name().substr(4) : std::string(); }

  // What the board answered to PROTOCOL_INFO when it was (last) opened.
  std::optional<protocol::UsbProtocolInfo> protocol_info() const { return pipe_->protocol_info(); }

 protected:
  HostResult<void> send_bytes(protocol::ByteView message) override;
  HostResult<std::optional<RawMessage>> receive_bytes(int64_t timeout_ns) override;

 private:
  std::unique_ptr<UsbBulkPipe> pipe_;
};

}  // namespace tetrapulse::host
