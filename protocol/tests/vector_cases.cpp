#include "vector_cases.hpp"

#include <cctype>

#include "golden_messages.hpp"

namespace tetrapulse::protocol::testing {

std::vector<VectorCase> vector_cases(const std::string& subfolder) {
  const auto files = read_hex_folder(vectors_dir() + "/" + subfolder);
  if (!files) return {VectorCase{"load_error", {}, files.error()}};
  if (files->empty()) return {VectorCase{"load_error", {}, subfolder + ": no .hex files"}};
  std::vector<VectorCase> cases;
  for (const HexFile& file : *files) {
    for (const HexRecord& record : file.records) cases.push_back({golden_key(file.stem, record.name), record, {}});
  }
  return cases;
}

std::string case_name(const ::testing::TestParamInfo<VectorCase>& info) {
  std::string name = info.param.key;
  for (char& c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0) c = '_';
  }
  return name;
}

Error expected_error(const std::string& record_name) {
  const std::string prefix = record_name.substr(0, record_name.find('.'));
  for (int e = 1; e < 256; ++e) {
    if (prefix == error_name(static_cast<Error>(e))) return static_cast<Error>(e);
  }
  return Error::kNone;
}

}  // namespace tetrapulse::protocol::testing
