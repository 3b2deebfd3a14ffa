#pragma once
// Vector records as GoogleTest parameters (one test per record), and record access that
// reports a missing record as a test failure.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "hex_vectors.hpp"
#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol::testing {

struct VectorCase {
  std::string key;   // golden_key(stem, record)
  HexRecord record;
  std::string load_error;  // set when the folder did not read: the case then fails with it
};

// GoogleTest shows a case by its key and origin, not as raw bytes.
inline void PrintTo(const VectorCase& c, std::ostream* os) { *os << c.key << " (" << c.record.origin << ")"; }

// Every record of every file in vectors/<subfolder>.
std::vector<VectorCase> vector_cases(const std::string& subfolder);

// The bytes of record `name` of `file`; a test failure (and no bytes) when it has none.
std::vector<uint8_t> record_bytes(const HexFile& file, const std::string& name);

// Attribute `key` of record `name` as a number; a test failure (and 0) when it is missing.
uint64_t record_number(const HexFile& file, const std::string& name, const std::string& key);

// A test name from a case key ("bad_value.identify_pattern" -> "bad_value_identify_pattern").
std::string case_name(const ::testing::TestParamInfo<VectorCase>& info);

// The Error a malformed record names in its error= attribute (error=bad_value -> kBadValue);
// kNone if it names none or no defined Error.
Error expected_error(const HexRecord& record);

}  // namespace tetrapulse::protocol::testing
