// Writes every record of the .hex vectors under a folder as one binary file: a libFuzzer
// seed corpus. Usage: protocol_vectors_to_corpus VECTORS_DIR OUT_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "hex_vectors.hpp"

namespace fs = std::filesystem;
using tetrapulse::protocol::testing::read_hex_file;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s VECTORS_DIR OUT_DIR\n", argv[0]);
    return 2;
  }
  std::error_code ec;
  fs::create_directories(argv[2], ec);
  int written = 0;
  for (const auto& entry : fs::recursive_directory_iterator(argv[1], ec)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".hex") continue;
    const auto file = read_hex_file(entry.path().string());
    if (!file) {
      std::fprintf(stderr, "%s\n", file.error().c_str());
      return 3;
    }
    for (const auto& record : file->records) {
      const fs::path out = fs::path(argv[2]) / (file->stem + "." + record.name);
      std::ofstream(out, std::ios::binary)
          .write(reinterpret_cast<const char*>(record.bytes.data()), static_cast<std::streamsize>(record.bytes.size()));
      ++written;
    }
  }
  if (ec || written == 0) {
    std::fprintf(stderr, "%s: no vectors read%s%s\n", argv[1], ec ? ": " : "", ec ? ec.message().c_str() : "");
    return 3;
  }
  return 0;
}
