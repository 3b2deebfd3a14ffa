#pragma once
// Requests, host -> board (SPEC.md §2.3). Field order is wire order; fields(io, m)
// lists them once for the encoder, the decoder and the formatter.
#include <array>
#include <cstdint>

#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message_type.hpp"

namespace tetrapulse::protocol {

// A message with an empty body.
template <MessageType kT>
struct EmptyMessage {
  static constexpr MessageType kType = kT;
  template <class Io, class Self>
  static void fields(Io&, Self&) {}
};

using GetInfo = EmptyMessage<MessageType::kGetInfo>;              // -> Info
using GetConfig = EmptyMessage<MessageType::kGetConfig>;          // -> ConfigReport
using GetStatus = EmptyMessage<MessageType::kGetStatus>;          // -> StatusReport
using PersistConfig = EmptyMessage<MessageType::kPersistConfig>;  // -> Ack
using FactoryReset = EmptyMessage<MessageType::kFactoryReset>;    // -> Ack
using UpdateVerify = EmptyMessage<MessageType::kUpdateVerify>;    // -> Ack{value = image CRC-32C}
using UpdateAbort = EmptyMessage<MessageType::kUpdateAbort>;      // -> Ack

// Replaces the running configuration (not yet persisted). -> Ack
struct SetConfig {
  static constexpr MessageType kType = MessageType::kSetConfig;
  Config config;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("config", m.config);
  }
};

enum class IdentifyPattern : uint8_t {
  kStop = 0,         // back to playing codes
  kBlinkAll = 1,     // all markers blink together
  kChase = 2,        // markers light one after another, 0..3
  kCountIndex = 3,   // marker i blinks i+1 times, then a pause
};

// Makes a board visible to a person. -> Ack
struct Identify {
  static constexpr MessageType kType = MessageType::kIdentify;
  IdentifyPattern pattern = IdentifyPattern::kStop;
  uint16_t duration_ms = 0;  // 0: until Identify{kStop}

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("pattern", m.pattern);
    io.field("duration_ms", m.duration_ms);
  }
};

enum class RebootMode : uint8_t { kApplication = 0, kBootloader = 1 };

// -> Ack, sent before the board resets.
struct Reboot {
  static constexpr MessageType kType = MessageType::kReboot;
  RebootMode mode = RebootMode::kApplication;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("mode", m.mode);
  }
};

// Starts a firmware update into the inactive slot. -> Ack{value = 0, the first expected offset}
struct UpdateBegin {
  static constexpr MessageType kType = MessageType::kUpdateBegin;
  uint32_t image_size = 0;  // whole image, header included, >= kImageHeaderSize
  uint32_t version = 0;     // pack_version(major, minor, patch) of the image
  uint32_t crc32c = 0;      // CRC-32C of the whole image

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("image_size", m.image_size);
    io.field("version", m.version);
    io.field("crc32c", m.crc32c);
  }
};

// `length` image bytes at byte `offset` of the image. -> Ack{value = next expected offset}
struct UpdateChunk {
  static constexpr MessageType kType = MessageType::kUpdateChunk;
  uint32_t offset = 0;
  uint16_t length = 0;  // 1..kMaxUpdateChunk; the data fills the rest of the message
  std::array<uint8_t, kMaxUpdateChunk> data{};

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("offset", m.offset);
    io.tail("length", m.length, "data", m.data);
  }
};

// Reads the LED edges the code player scheduled, from sequence number `first` on. -> LedLog
struct GetLedLog {
  static constexpr MessageType kType = MessageType::kGetLedLog;
  uint32_t first = 0;

  template <class Io, class Self>
  static void fields(Io& io, Self& m) {
    io.field("first", m.first);
  }
};

}  // namespace tetrapulse::protocol
