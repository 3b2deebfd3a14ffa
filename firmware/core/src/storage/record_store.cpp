#include "tetrapulse/fw/storage/record_store.hpp"

#include "tetrapulse/protocol/crc.hpp"

namespace tetrapulse::fw {
namespace {

using protocol::ByteReader;
using protocol::ByteView;
using protocol::ByteWriter;
using protocol::Error;
using protocol::Status;

constexpr uint32_t kSectorMagic = 0x53525054;  // "TPRS"
constexpr uint16_t kRecordMagic = 0x5243;      // "CR"
constexpr uint8_t kErased = 0xFF;
constexpr size_t kChunk = 64;

constexpr uint32_t aligned(uint32_t n) {
  return (n + RecordStore::kAlignment - 1) / RecordStore::kAlignment * RecordStore::kAlignment;
}
constexpr uint32_t record_size(size_t payload) { return aligned(static_cast<uint32_t>(RecordStore::kHeaderSize + payload)); }

// Newer generation, allowing for wrap-around.
bool newer(uint32_t a, uint32_t b) { return static_cast<int32_t>(a - b) > 0; }

uint32_t record_crc(const uint8_t* header12, const uint8_t* payload, size_t length) {
  protocol::Crc32c crc;
  crc.update(header12, 12);
  crc.update(payload, length);
  return crc.value();
}

}  // namespace

bool RecordStore::read_header(size_t sector, uint32_t* generation) const {
  uint8_t h[kHeaderSize];
  if (!flash_.read(sectors_[sector].address, h, sizeof(h))) return false;
  ByteReader r(h, sizeof(h));
  const uint32_t magic = r.u32();
  const uint32_t gen = r.u32();
  const uint32_t reserved = r.u32();
  const uint32_t crc = r.u32();
  if (magic != kSectorMagic || reserved != 0 || crc != protocol::crc32c(h, 12)) return false;
  *generation = gen;
  return true;
}

Status RecordStore::open() {
  for (Entry& e : entries_) e = Entry{};
  have_active_ = false;
  torn_ = false;
  next_seq_ = 1;
  uint32_t gen[2] = {0, 0};
  const bool valid[2] = {read_header(0, &gen[0]), read_header(1, &gen[1])};
  if (!valid[0] && !valid[1]) return {};
  active_ = (valid[0] && valid[1]) ? (newer(gen[1], gen[0]) ? 1 : 0) : (valid[0] ? 0 : 1);
  generation_ = gen[active_];
  have_active_ = true;
  return scan(active_);
}

Status RecordStore::scan(size_t sector) {
  const FlashRegion& region = sectors_[sector];
  uint32_t pos = region.address + kHeaderSize;
  uint8_t payload[kMaxPayload];
  while (pos + kHeaderSize <= region.end()) {
    uint8_t h[kHeaderSize];
    if (!flash_.read(pos, h, sizeof(h))) return Error::kFlashError;
    bool blank = true;
    for (uint8_t b : h) blank = blank && b == kErased;
    if (blank) break;
    ByteReader r(h, sizeof(h));
    const uint16_t magic = r.u16();
    const uint8_t key = r.u8();
    const uint8_t zero = r.u8();
    const uint16_t length = r.u16();
    const uint16_t zero2 = r.u16();
    const uint32_t seq = r.u32();
    const uint32_t crc = r.u32();
    if (magic != kRecordMagic || zero != 0 || zero2 != 0 || length > kMaxPayload ||
        pos + record_size(length) > region.end()) {
      torn_ = true;
      break;
    }
    if (!flash_.read(pos + kHeaderSize, payload, length)) return Error::kFlashError;
    if (record_crc(h, payload, length) != crc) {
      torn_ = true;
      break;
    }
    if (key >= 1 && key <= kMaxKeys) entries_[key] = Entry{true, pos, length, seq};
    if (static_cast<int32_t>(seq - next_seq_) >= 0) next_seq_ = seq + 1;
    pos += record_size(length);
  }
  write_at_ = pos;
  // Whatever follows the last good record must be erased, or the sector ends torn (a
  // record cut short by a power loss, whose header may itself be blank).
  for (uint32_t a = pos; !torn_ && a < region.end(); a += kChunk) {
    uint8_t buf[kChunk];
    const uint32_t n = region.end() - a < kChunk ? region.end() - a : static_cast<uint32_t>(kChunk);
    if (!flash_.read(a, buf, n)) return Error::kFlashError;
    for (uint32_t i = 0; i < n; ++i) {
      if (buf[i] != kErased) torn_ = true;
    }
  }
  return {};
}

Status RecordStore::append(size_t sector, uint32_t at, uint8_t key, ByteView payload, uint32_t seq) {
  uint8_t buf[kHeaderSize + kMaxPayload + kAlignment];
  const uint32_t size = record_size(payload.size);
  if (at + size > sectors_[sector].end()) return Error::kBufferTooSmall;
  ByteWriter w(buf, sizeof(buf));
  w.u16(kRecordMagic);
  w.u8(key);
  w.u8(0);
  w.u16(static_cast<uint16_t>(payload.size));
  w.u16(0);
  w.u32(seq);
  w.u32(record_crc(buf, payload.data, payload.size));
  w.bytes(payload.data, payload.size);
  while (w.size() < size) w.u8(kErased);
  return flash_.program(at, ByteView{buf, size});
}

Status RecordStore::write(uint8_t key, ByteView payload) {
  if (key < 1 || key > kMaxKeys || payload.size > kMaxPayload) return Error::kBadValue;
  if (!have_active_ || torn_ || write_at_ + record_size(payload.size) > sectors_[active_].end()) {
    return compact(key, payload);
  }
  const uint32_t at = write_at_;
  const uint32_t seq = next_seq_++;
  const Status s = append(active_, at, key, payload, seq);
  if (!s) {
    torn_ = true;  // a partial record may be there: the next write compacts
    return Error::kFlashError;
  }
  entries_[key] = Entry{true, at, static_cast<uint16_t>(payload.size), seq};
  write_at_ = at + record_size(payload.size);
  return {};
}

Status RecordStore::compact(uint8_t key, ByteView payload) {
  const size_t target = have_active_ ? 1 - active_ : 0;
  const FlashRegion& region = sectors_[target];
  if (!flash_.erase_sector(region.address)) return Error::kFlashError;
  // Erase must really have left 0xFF everywhere before anything is written there.
  for (uint32_t a = region.address; a < region.end(); a += kChunk) {
    uint8_t buf[kChunk];
    const uint32_t n = region.end() - a < kChunk ? region.end() - a : static_cast<uint32_t>(kChunk);
    if (!flash_.read(a, buf, n)) return Error::kFlashError;
    for (uint32_t i = 0; i < n; ++i) {
      if (buf[i] != kErased) return Error::kFlashError;
    }
  }
  uint32_t pos = region.address + kHeaderSize;
  uint8_t copy[kMaxPayload];
  for (uint8_t k = 1; k <= kMaxKeys; ++k) {
    const Entry& e = entries_[k];
    if (!e.present || k == key || !have_active_) continue;
    if (!flash_.read(e.address + kHeaderSize, copy, e.length)) return Error::kFlashError;
    if (!append(target, pos, k, ByteView{copy, e.length}, e.seq)) return Error::kFlashError;
    pos += record_size(e.length);
  }
  if (!append(target, pos, key, payload, next_seq_)) return Error::kFlashError;
  // The commit point: the sector header, written last.
  uint8_t h[kHeaderSize];
  ByteWriter w(h, sizeof(h));
  w.u32(kSectorMagic);
  w.u32(have_active_ ? generation_ + 1 : 1);
  w.u32(0);
  w.u32(protocol::crc32c(h, 12));
  if (!flash_.program(region.address, ByteView{h, sizeof(h)})) return Error::kFlashError;
  ++compactions_;
  return open();
}

protocol::Result<size_t> RecordStore::read(uint8_t key, uint8_t* out, size_t capacity) const {
  if (!contains(key)) return Error::kInvalidState;
  const Entry& e = entries_[key];
  if (e.length > capacity) return Error::kBufferTooSmall;
  if (!flash_.read(e.address + kHeaderSize, out, e.length)) return Error::kFlashError;
  return static_cast<size_t>(e.length);
}

bool RecordStore::contains(uint8_t key) const { return key >= 1 && key <= kMaxKeys && entries_[key].present; }

}  // namespace tetrapulse::fw
