#include "hex_vectors.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tetrapulse::protocol::testing {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

}  // namespace

const HexRecord* HexFile::find(const std::string& name) const {
  for (const HexRecord& r : records) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

tl::expected<HexFile, std::string> read_hex_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return tl::make_unexpected(path + ": cannot open");
  HexFile file;
  file.path = path;
  file.stem = std::filesystem::path(path).stem().string();
  // The unnamed first record exists until a [name] shows it was only a file comment.
  file.records.push_back(HexRecord{file.stem, {}, {}, path + ":1"});
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number);
    const std::string text = trim(line);
    const auto hash = line.find('#');
    if (!text.empty() && text[0] == '#') {
      std::string& d = file.records.back().description;
      d += (d.empty() ? "" : "\n") + trim(text.substr(1));
      continue;
    }
    const std::string content = trim(line.substr(0, hash));
    if (content.empty()) continue;
    if (content.front() == '[') {
      if (content.back() != ']' || content.size() < 3) {
        return tl::make_unexpected(where + ": a record name is written [name]");
      }
      const std::string name = content.substr(1, content.size() - 2);
      if (file.find(name) != nullptr) return tl::make_unexpected(where + ": record [" + name + "] repeated");
      // A file that starts with named records: its leading comments were not a record.
      if (file.records.size() == 1 && file.records[0].bytes.empty()) file.records.clear();
      file.records.push_back(HexRecord{name, {}, {}, where});
      continue;
    }
    std::istringstream tokens(content);
    std::string token;
    while (tokens >> token) {
      if (token.size() % 2 != 0) return tl::make_unexpected(where + ": '" + token + "' has an odd number of hex digits");
      for (size_t i = 0; i < token.size(); i += 2) {
        const int hi = hex_digit(token[i]);
        const int lo = hex_digit(token[i + 1]);
        if (hi < 0 || lo < 0) return tl::make_unexpected(where + ": '" + token + "' is not hex");
        file.records.back().bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
      }
    }
  }
  return file;
}

tl::expected<std::vector<HexFile>, std::string> read_hex_folder(const std::string& folder) {
  std::error_code ec;
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".hex") paths.push_back(entry.path().string());
  }
  if (ec) return tl::make_unexpected(folder + ": " + ec.message());
  std::sort(paths.begin(), paths.end());
  std::vector<HexFile> files;
  for (const std::string& path : paths) {
    auto file = read_hex_file(path);
    if (!file) return tl::make_unexpected(file.error());
    files.push_back(std::move(*file));
  }
  return files;
}

std::string vectors_dir() { return TETRAPULSE_PROTOCOL_VECTORS_DIR; }

std::string to_hex(const std::vector<uint8_t>& bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < bytes.size(); ++i) {
    if (i > 0) s += ' ';
    s += kHex[bytes[i] >> 4];
    s += kHex[bytes[i] & 0xF];
  }
  return s;
}

}  // namespace tetrapulse::protocol::testing
