#pragma once
// Golden vector files (protocol/vectors/, SPEC.md §1.1): text any implementation can read.
//
//   # comment to the end of the line, anywhere
//   [record_name]            starts a named record (unique in the file); its content may
//                            follow on the same line. Content before any [name] forms a
//                            record named after the file ("identify" for identify.hex).
//   01 05 07  0288 13        hex bytes; a token may hold several bytes (even digit count)
//   id=0x0041FF00            an attribute of the record: key=value, value without spaces
//
// A record's description is the text of the whole-line comments inside it (after its
// [name] line, or from the top of the file for the unnamed record).
#include <tl/expected.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tetrapulse::protocol::testing {

struct HexRecord {
  std::string name;
  std::string description;     // whole-line comments, joined by '\n'
  std::vector<uint8_t> bytes;
  std::map<std::string, std::string> attributes;
  std::string origin;          // "path:line" where the record starts

  // The attribute's text, or null.
  const std::string* attribute(const std::string& key) const;
  // The attribute as a number (decimal, or hex after 0x); the error names the record.
  tl::expected<uint64_t, std::string> number(const std::string& key) const;
};

struct HexFile {
  std::string path;
  std::string stem;            // file name without folder and ".hex"
  std::string description;     // comments before the first [name] when they form no record
  std::vector<HexRecord> records;

  const HexRecord* find(const std::string& name) const;
  // Records whose name starts with `prefix`, in file order ("frame." -> frame.0, frame.1, ...).
  std::vector<const HexRecord*> starting_with(const std::string& prefix) const;
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
