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

bool valid_key(const std::string& key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) != 0 || std::isdigit(static_cast<unsigned char>(c)) != 0 ||
           c == '_';
  });
}

// Adds the tokens of one line (bytes and attributes) to `record`; an error says what is wrong.
std::string add_tokens(const std::string& content, HexRecord* record) {
  std::istringstream tokens(content);
  std::string token;
  while (tokens >> token) {
    const auto eq = token.find('=');
    if (eq != std::string::npos) {
      const std::string key = token.substr(0, eq);
      if (!valid_key(key) || eq + 1 == token.size()) return "'" + token + "' is not key=value";
      if (!record->attributes.emplace(key, token.substr(eq + 1)).second) return "attribute " + key + " repeated";
      continue;
    }
    if (token.size() % 2 != 0) return "'" + token + "' has an odd number of hex digits";
    for (size_t i = 0; i < token.size(); i += 2) {
      const int hi = hex_digit(token[i]);
      const int lo = hex_digit(token[i + 1]);
      if (hi < 0 || lo < 0) return "'" + token + "' is not hex";
      record->bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
    }
  }
  return {};
}

}  // namespace

const std::string* HexRecord::attribute(const std::string& key) const {
  const auto it = attributes.find(key);
  return it == attributes.end() ? nullptr : &it->second;
}

tl::expected<uint64_t, std::string> HexRecord::number(const std::string& key) const {
  const std::string* text = attribute(key);
  if (text == nullptr) return tl::make_unexpected(origin + ": [" + name + "] has no " + key + "=");
  const bool hex = text->size() > 2 && (*text)[0] == '0' && ((*text)[1] == 'x' || (*text)[1] == 'X');
  const std::string digits = hex ? text->substr(2) : *text;
  uint64_t value = 0;
  for (char c : digits) {
    const int d = hex ? hex_digit(c) : (std::isdigit(static_cast<unsigned char>(c)) != 0 ? c - '0' : -1);
    const uint64_t base = hex ? 16 : 10;
    if (d < 0 || value > (UINT64_MAX - static_cast<uint64_t>(d)) / base) {
      return tl::make_unexpected(origin + ": [" + name + "] " + key + "=" + *text + " is not a 64-bit number");
    }
    value = value * base + static_cast<uint64_t>(d);
  }
  return value;
}

const HexRecord* HexFile::find(const std::string& name) const {
  for (const HexRecord& r : records) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

std::vector<const HexRecord*> HexFile::starting_with(const std::string& prefix) const {
  std::vector<const HexRecord*> out;
  for (const HexRecord& r : records) {
    if (r.name.compare(0, prefix.size(), prefix) == 0) out.push_back(&r);
  }
  return out;
}

tl::expected<HexFile, std::string> read_hex_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return tl::make_unexpected(path + ": cannot open");
  HexFile file;
  file.path = path;
  file.stem = std::filesystem::path(path).stem().string();
  // The unnamed first record exists until a [name] shows it was only a file comment.
  file.records.push_back(HexRecord{file.stem, {}, {}, {}, path + ":1"});
  bool unnamed = true;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number);
    const std::string text = trim(line);
    if (!text.empty() && text[0] == '#') {
      std::string& d = file.records.back().description;
      d += (d.empty() ? "" : "\n") + trim(text.substr(1));
      continue;
    }
    std::string content = trim(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    if (content.front() == '[') {
      const auto close = content.find(']');
      if (close == std::string::npos || close < 2) return tl::make_unexpected(where + ": a record name is written [name]");
      const std::string name = content.substr(1, close - 1);
      if (file.find(name) != nullptr) return tl::make_unexpected(where + ": record [" + name + "] repeated");
      // A file that starts with named records: its leading comments were not a record.
      if (unnamed && file.records.front().bytes.empty() && file.records.front().attributes.empty()) {
        file.description = file.records.front().description;
        file.records.clear();
      }
      unnamed = false;
      file.records.push_back(HexRecord{name, {}, {}, {}, where});
      content = content.substr(close + 1);
    }
    const std::string error = add_tokens(content, &file.records.back());
    if (!error.empty()) return tl::make_unexpected(where + ": " + error);
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
