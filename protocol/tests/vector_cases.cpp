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

std::vector<uint8_t> record_bytes(const HexFile& file, const std::string& name) {
  const HexRecord* r = file.find(name);
  EXPECT_NE(r, nullptr) << file.path << " has no [" << name << "]";
  return r != nullptr ? r->bytes : std::vector<uint8_t>{};
}

uint64_t record_number(const HexFile& file, const std::string& name, const std::string& key) {
  const HexRecord* r = file.find(name);
  if (r == nullptr) {
    ADD_FAILURE() << file.path << " has no [" << name << "]";
    return 0;
  }
  const auto v = r->number(key);
  EXPECT_TRUE(v.has_value()) << v.error();
  return v.value_or(0);
}

std::string case_name(const ::testing::TestParamInfo<VectorCase>& info) {
  std::string name = info.param.key;
  for (char& c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0) c = '_';
  }
  return name;
}

Error expected_error(const HexRecord& record) {
  const std::string* name = record.attribute("error");
  for (int e = 1; name != nullptr && e < 256; ++e) {
    if (*name == error_name(static_cast<Error>(e))) return static_cast<Error>(e);
  }
  return Error::kNone;
}

}  // namespace tetrapulse::protocol::testing
