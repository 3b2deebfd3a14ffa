// Writes the golden vectors as binary seed inputs for the fuzz targets:
//   write_fuzz_seeds <vectors dir> <output dir>
// creates <output dir>/{can,uart,usb_bulk,dfu_status}/<vector name>.bin.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_input.hpp"
#include "vector_file.hpp"

namespace {

namespace fs = std::filesystem;
using tetrapulse::protocol::CanFrame;
using tetrapulse::protocol::testing::VectorFile;

bool write(const fs::path& dir, const std::string& source, const std::vector<uint8_t>& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / (fs::path(source).stem().string() + ".bin"), std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

std::vector<VectorFile> read(const fs::path& dir) {
  auto files = tetrapulse::protocol::testing::read_vector_dir(dir.string());
  if (!files) {
    std::fprintf(stderr, "write_fuzz_seeds: %s\n", files.error().c_str());
    return {};
  }
  return std::move(*files);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: write_fuzz_seeds <vectors dir> <output dir>\n");
    return 2;
  }
  const fs::path vectors = argv[1], out = argv[2];
  bool ok = true;
  for (const VectorFile& f : read(vectors / "can")) {
    std::vector<uint8_t> seed;
    for (const auto* r : f.all("frame")) {
      CanFrame frame;
      frame.id = static_cast<uint32_t>(r->fields.at("id"));
      for (uint8_t b : r->bytes) frame.data[frame.size++] = b;
      tetrapulse::protocol::fuzz::append_can_frame(frame, 1, &seed);
    }
    ok = write(out / "can", f.path, seed) && ok;
  }
  for (const VectorFile& f : read(vectors / "uart")) {
    std::vector<uint8_t> seed{0};  // first byte: feed piece size
    const auto& frame = f.first("frame")->bytes;
    seed.insert(seed.end(), frame.begin(), frame.end());
    ok = write(out / "uart", f.path, seed) && ok;
  }
  for (const VectorFile& f : read(vectors / "usb")) {
    const std::string name = fs::path(f.path).filename().string();
    if (name.rfind("bulk_", 0) == 0) {
      // As packets on the bus: 64-byte packets, then the short one (maybe a ZLP).
      const auto& t = f.first("transfer")->bytes;
      std::vector<uint8_t> seed;
      for (size_t at = 0;; at += 64) {
        const size_t n = t.size() - at < 64 ? t.size() - at : 64;
        tetrapulse::protocol::fuzz::append_usb_packet(t.data() + at, n, &seed);
        if (n < 64) break;
      }
      ok = write(out / "usb_bulk", f.path, seed) && ok;
      ok = write(out / "usb_bulk", "whole_" + name, t) && ok;
    } else if (const auto* bytes = f.first("bytes")) {
      ok = write(out / "dfu_status", f.path, bytes->bytes) && ok;
    }
  }
  return ok ? 0 : 1;
}
