#include "vector_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tetrapulse::protocol::testing {
namespace {

bool parse_number(const std::string& text, uint64_t* out) {
  if (text.empty()) return false;
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const std::string digits = hex ? text.substr(2) : text;
  if (digits.empty() || digits.size() > 16) return false;
  uint64_t v = 0;
  for (char c : digits) {
    const int d = std::isdigit(static_cast<unsigned char>(c)) ? c - '0'
                  : (hex && std::isxdigit(static_cast<unsigned char>(c)))
                      ? std::tolower(static_cast<unsigned char>(c)) - 'a' + 10
                      : -1;
    if (d < 0) return false;
    v = v * (hex ? 16 : 10) + static_cast<uint64_t>(d);
  }
  *out = v;
  return true;
}

bool parse_byte(const std::string& text, uint8_t* out) {
  uint64_t v = 0;
  if (text.size() != 2 || !parse_number("0x" + text, &v)) return false;
  *out = static_cast<uint8_t>(v);
  return true;
}

}  // namespace

std::vector<const VectorRecord*> VectorFile::all(const std::string& label) const {
  std::vector<const VectorRecord*> out;
  for (const VectorRecord& r : records) {
    if (r.label == label) out.push_back(&r);
  }
  return out;
}

const VectorRecord* VectorFile::first(const std::string& label) const {
  for (const VectorRecord& r : records) {
    if (r.label == label) return &r;
  }
  return nullptr;
}

tl::expected<VectorFile, std::string> read_vector_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return tl::unexpected(path + ": cannot open");
  VectorFile file;
  file.path = path;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto where = [&] { return path + ":" + std::to_string(number) + ": "; };
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      file.comments.push_back(line.substr(first + 1));
      continue;
    }
    VectorRecord record;
    std::string rest = line;
    const size_t colon = line.find(':');
    if (colon != std::string::npos) {
      record.label = line.substr(first, colon - first);
      rest = line.substr(colon + 1);
    }
    std::istringstream tokens(rest);
    std::string token;
    while (tokens >> token) {
      const size_t eq = token.find('=');
      if (eq == std::string::npos) {
        uint8_t b = 0;
        if (!parse_byte(token, &b)) return tl::unexpected(where() + "'" + token + "' is not a hex byte");
        record.bytes.push_back(b);
        continue;
      }
      const std::string name = token.substr(0, eq);
      const std::string value = token.substr(eq + 1);
      if (name == "data") {
        uint8_t b = 0;
        if (!parse_byte(value, &b)) return tl::unexpected(where() + "'" + token + "' is not data=<hex byte>");
        record.bytes.push_back(b);
        continue;
      }
      uint64_t v = 0;
      if (!parse_number(value, &v)) return tl::unexpected(where() + "'" + token + "' has no number");
      record.fields[name] = v;
    }
    file.records.push_back(std::move(record));
  }
  return file;
}

tl::expected<std::vector<std::string>, std::string> list_vector_files(const std::string& dir) {
  std::error_code ec;
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".txt") out.push_back(entry.path().string());
  }
  if (ec) return tl::unexpected(dir + ": " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

tl::expected<std::vector<VectorFile>, std::string> read_vector_dir(const std::string& dir,
                                                                   const std::string& prefix) {
  const auto paths = list_vector_files(dir);
  if (!paths) return tl::unexpected(paths.error());
  std::vector<VectorFile> files;
  for (const std::string& path : *paths) {
    if (std::filesystem::path(path).filename().string().rfind(prefix, 0) != 0) continue;
    auto file = read_vector_file(path);
    if (!file) return tl::unexpected(file.error());
    files.push_back(std::move(*file));
  }
  if (files.empty()) return tl::unexpected(dir + ": no " + prefix + "*.txt vector files");
  return files;
}

std::string vectors_dir(const std::string& part) {
  return std::string(TETRAPULSE_PROTOCOL_VECTORS_DIR) + "/" + part;
}

}  // namespace tetrapulse::protocol::testing
