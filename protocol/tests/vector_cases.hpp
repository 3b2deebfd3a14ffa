#pragma once
// Vector records as GoogleTest parameters: one test per record.
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

// A test name from a case key ("bad_value.identify_pattern" -> "bad_value_identify_pattern").
std::string case_name(const ::testing::TestParamInfo<VectorCase>& info);

// The Error whose error_name() begins a malformed record's name ("bad_value.x" -> kBadValue);
// kNone if there is none.
Error expected_error(const std::string& record_name);

}  // namespace tetrapulse::protocol::testing
