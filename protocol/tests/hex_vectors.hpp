#pragma once
// Golden byte vectors (protocol/vectors/): text files any implementation can read.
//
//   # comment to the end of the line, anywhere
//   [record_name]            starts a named record; bytes before any [name] form a record
//                            named after the file (e.g. "identify" for identify.hex)
//   01 05 07  0288 13        hex bytes; a token may hold several bytes (even digit count)
//
// A record's description is the text of the whole-line comments inside it (after its
// [name] line, or from the top of the file for the unnamed record).
#include <tl/expected.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace tetrapulse::protocol::testing {

struct HexRecord {
  std::string name;
  std::string description;     // whole-line comments, joined by '\n'
  std::vector<uint8_t> bytes;
  std::string origin;          // "path:line" where the record starts
};

struct HexFile {
  std::string path;
  std::string stem;            // file name without folder and ".hex"
  std::vector<HexRecord> records;

  const HexRecord* find(const std::string& name) const;
};

// Parses one file; the error names the file, line and what is wrong.
tl::expected<HexFile, std::string> read_hex_file(const std::string& path);

// Every *.hex file directly in `folder`, sorted by name.
tl::expected<std::vector<HexFile>, std::string> read_hex_folder(const std::string& folder);

// The vectors folder of this source tree (compile definition TETRAPULSE_PROTOCOL_VECTORS_DIR).
std::string vectors_dir();

// "01 05 07" style, for failure messages.
std::string to_hex(const std::vector<uint8_t>& bytes);

}  // namespace tetrapulse::protocol::testing
