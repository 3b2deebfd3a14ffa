#pragma once
// Test-side reader of golden vector files (protocol/vectors/, SPEC.md §4.6, §5.7, §6.4).
//
// Lines starting with '#' are comments. Every other non-blank line is a record:
//   [label:] token token ...
// where a token is either `name=value` (value decimal or 0x-prefixed hex) or a byte
// as two hex digits; `data=XX` is the first byte of the record's bytes, not a field.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <tl/expected.hpp>

namespace tetrapulse::protocol::testing {

struct VectorRecord {
  std::string label;                      // text before ':' ("" when none)
  std::map<std::string, uint64_t> fields;
  std::vector<uint8_t> bytes;
};

struct VectorFile {
  std::string path;
  std::vector<std::string> comments;
  std::vector<VectorRecord> records;

  // Records with this label, in file order.
  std::vector<const VectorRecord*> all(const std::string& label) const;
  // The first record with this label, or null.
  const VectorRecord* first(const std::string& label) const;
};

// An error names the file and line.
tl::expected<VectorFile, std::string> read_vector_file(const std::string& path);

// Every *.txt file in `dir` (sorted), or the reason it cannot be listed.
tl::expected<std::vector<std::string>, std::string> list_vector_files(const std::string& dir);

// Every *.txt file in `dir` whose name starts with `prefix`, read; the first error
// stops it, and finding no file is an error.
tl::expected<std::vector<VectorFile>, std::string> read_vector_dir(const std::string& dir,
                                                                   const std::string& prefix = "");

// protocol/vectors/<part>, from the build's TETRAPULSE_PROTOCOL_VECTORS_DIR.
std::string vectors_dir(const std::string& part);

}  // namespace tetrapulse::protocol::testing
