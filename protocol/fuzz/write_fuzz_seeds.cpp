// Writes the golden vectors (protocol/vectors, SPEC.md §1.1) as binary seed inputs, one
// folder per fuzz target, in the input form each target reads (fuzz_input.hpp):
//   protocol_write_fuzz_seeds <output dir>
// creates <output dir>/{messages,config,image,can,uart,cobs,usb_bulk,usb_message_out,dfu_status,
// protocol_info}/<file>.<record>.bin.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_input.hpp"
#include "tetrapulse/protocol/config.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "transport_testing.hpp"
#include "transport_vectors.hpp"

namespace {

namespace fs = std::filesystem;
using tetrapulse::protocol::testing::HexFile;
using Bytes = std::vector<uint8_t>;

class SeedWriter {
 public:
  explicit SeedWriter(fs::path out) : out_(std::move(out)) {}

  void write(const std::string& corpus, const std::string& name, const Bytes& bytes) {
    const fs::path dir = out_ / corpus;
    std::error_code ec;
    fs::create_directories(dir, ec);
    std::ofstream file(dir / (name + ".bin"), std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!file) fail(dir.string() + "/" + name + ".bin: cannot write");
    ++written_;
  }

  // The files of vectors/<folder> whose names start with `prefix`.
  std::vector<HexFile> read(const std::string& folder, const std::string& prefix = "") {
    auto files = tetrapulse::protocol::testing::read_vectors(folder, prefix);
    if (!files) {
      fail(files.error());
      return {};
    }
    return std::move(*files);
  }

  // The bytes of record `name`, or a failure when `file` lacks it.
  Bytes record(const HexFile& file, const std::string& name) {
    const auto* r = file.find(name);
    if (r == nullptr) fail(file.path + ": no [" + name + "]");
    return r != nullptr ? r->bytes : Bytes{};
  }

  void fail(const std::string& why) {
    std::fprintf(stderr, "write_fuzz_seeds: %s\n", why.c_str());
    ok_ = false;
  }
  bool ok() const { return ok_ && written_ > 0; }

 private:
  fs::path out_;
  bool ok_ = true;
  size_t written_ = 0;
};

// Every record as it is: messages and image headers, golden and malformed.
void write_records(SeedWriter& w, const std::string& corpus, const std::string& folder) {
  for (const HexFile& f : w.read(folder)) {
    for (const auto& r : f.records) w.write(corpus, f.stem + "." + r.name, r.bytes);
  }
}

// Each golden message as a MESSAGE_OUT control transfer, and the Config of SetConfig and
// ConfigReport on its own.
void write_message_forms(SeedWriter& w) {
  namespace tp = tetrapulse::protocol;
  for (const HexFile& f : w.read("messages")) {
    for (const auto& r : f.records) {
      const std::string name = f.stem + "." + r.name;
      Bytes transfer;
      tp::fuzz::append_usb_setup(static_cast<uint16_t>(r.bytes.size()), &transfer);
      for (const Bytes& p : tp::testing::usb_packets(r.bytes, false)) {
        tp::fuzz::append_usb_packet(p.data(), p.size(), &transfer);
      }
      w.write("usb_message_out", name, transfer);
      const bool has_config = r.bytes.size() == tp::kMessageHeaderSize + tp::kConfigSize &&
                              (r.bytes[1] == static_cast<uint8_t>(tp::MessageType::kSetConfig) ||
                               r.bytes[1] == static_cast<uint8_t>(tp::MessageType::kConfigReport));
      if (has_config) w.write("config", name, Bytes(r.bytes.begin() + tp::kMessageHeaderSize, r.bytes.end()));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <output dir>\n", argv[0]);
    return 2;
  }
  namespace fuzz = tetrapulse::protocol::fuzz;
  SeedWriter w(argv[1]);
  write_records(w, "messages", "messages");
  write_records(w, "messages", "messages/malformed");
  write_message_forms(w);
  write_records(w, "image", "image");
  write_records(w, "image", "image/malformed");
  for (const HexFile& f : w.read("can")) {
    const auto transfer = tetrapulse::protocol::testing::can_transfer_vector(f);
    if (!transfer) {
      w.fail(transfer.error());
      continue;
    }
    Bytes seed;
    for (const auto& frame : transfer->frames) fuzz::append_can_frame(frame, 1, &seed);
    w.write("can", f.stem, seed);
  }
  for (const HexFile& f : w.read("uart")) {
    Bytes seed{0};  // first byte: the size of the pieces the stream is fed in
    const Bytes frame = w.record(f, "frame");
    seed.insert(seed.end(), frame.begin(), frame.end());
    w.write("uart", f.stem, seed);
    if (!frame.empty()) w.write("cobs", f.stem, Bytes(frame.begin(), frame.end() - 1));  // without the delimiter
  }
  for (const HexFile& f : w.read("usb", "bulk_")) {
    // As packets on the bus: 64-byte packets, then the short one (maybe a ZLP).
    const Bytes t = w.record(f, "transfer");
    Bytes seed;
    for (const Bytes& p : tetrapulse::protocol::testing::usb_packets(t)) fuzz::append_usb_packet(p.data(), p.size(), &seed);
    w.write("usb_bulk", f.stem, seed);
    w.write("usb_bulk", "whole_" + f.stem, t);
  }
  for (const HexFile& f : w.read("usb", "dfu_status_")) w.write("dfu_status", f.stem, w.record(f, "bytes"));
  for (const HexFile& f : w.read("usb", "protocol_info")) w.write("protocol_info", f.stem, w.record(f, "bytes"));
  return w.ok() ? 0 : 1;
}
