// SPEC.md's tables against the code: the message types of §2.2 (code, name, direction,
// body size of every golden message), the field tables of §2.3-2.6 (offset, size, type and
// name of every field, in order, as the encoder and decoder walk them), the errors of §3 and
// the CAN faults of §4.4.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "../src/field_io.hpp"
#include "golden_messages.hpp"
#include "hex_vectors.hpp"
#include "message_testing.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"

namespace tetrapulse::protocol::testing {
namespace {

using Row = std::vector<std::string>;

std::vector<std::string> spec_lines() {
  std::ifstream in(vectors_dir() + "/../SPEC.md");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(' ');
  const size_t b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// The cells of a table line; `\|` is a pipe inside a cell.
Row cells(const std::string& line) {
  Row row;
  std::string cell;
  for (size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      row.push_back(trim(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return row;
}

// The body rows of the first table after the first line that contains `marker`; none if
// there is no such line.
std::vector<Row> table_after(const std::vector<std::string>& lines, const std::string& marker) {
  size_t i = 0;
  while (i < lines.size() && lines[i].find(marker) == std::string::npos) ++i;
  while (i < lines.size() && lines[i].rfind("|", 0) != 0) ++i;
  std::vector<Row> rows;
  for (i += 2; i < lines.size() && lines[i].rfind("|", 0) == 0; ++i) rows.push_back(cells(lines[i]));
  return rows;
}

// "UpdateChunk" -> "update_chunk".
std::string snake_case(const std::string& camel) {
  std::string s;
  for (char c : camel) {
    if (std::isupper(static_cast<unsigned char>(c)) != 0) {
      if (!s.empty()) s += '_';
      s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      s += c;
    }
  }
  return s;
}

// The rows of a field table as the code walks the fields: offset, size, type, name.
// Groups (structs, array items) are one row; a tail is its count's row, then the items'.
class FieldTableWalker : public detail::FieldWalker<FieldTableWalker> {
 public:
  template <class T>
  void scalar(const char* name, const T&) {
    using W = typename detail::WireInt<T>::type;
    add(name, sizeof(W), std::string(std::is_signed_v<W> ? "i" : "u") + std::to_string(8 * sizeof(W)));
  }
  void bytes(const char* name, const uint8_t*, size_t n) { add(name, n, "bytes[" + std::to_string(n) + "]"); }
  void open(const char* name, long index) {
    if (depth_++ > 0) return;
    group_start_ = offset_;
    group_name_ = index < 0 ? name : std::string(name) + "[" + std::to_string(index) + "]";
  }
  void close() {
    if (--depth_ > 0) return;
    rows_.push_back({std::to_string(group_start_), std::to_string(offset_ - group_start_), "struct", group_name_});
  }
  template <class Count, class Array>
  void tail(const char* count_name, Count& count, const char* items_name, Array&) {
    scalar(count_name, count);
    using Item = typename detail::ArrayTraits<std::remove_const_t<Array>>::Item;
    if constexpr (std::is_same_v<Item, uint8_t>) {
      rows_.push_back({std::to_string(offset_), count_name, "bytes", items_name});
    } else {
      const std::string size = std::to_string(detail::encoded_size<Item>()) + "·" + count_name;
      rows_.push_back({std::to_string(offset_), size, "struct", items_name});
    }
  }

  const std::vector<Row>& rows() const { return rows_; }

 private:
  void add(const char* name, size_t size, const std::string& type) {
    if (depth_ == 0) rows_.push_back({std::to_string(offset_), std::to_string(size), type, name});
    offset_ += size;
  }
  std::vector<Row> rows_;
  size_t offset_ = 0;
  int depth_ = 0;
  size_t group_start_ = 0;
  std::string group_name_;
};

template <class T>
std::vector<Row> code_rows() {
  T value{};
  FieldTableWalker walker;
  T::fields(walker, value);
  return walker.rows();
}

// Compares the code's rows with a SPEC table's first four columns; a struct row's type in
// SPEC is the struct's name (capitalised), a scalar's is its wire type.
void expect_same_fields(const std::vector<Row>& code, const std::vector<Row>& spec, const std::string& what) {
  ASSERT_EQ(code.size(), spec.size()) << what << ": fields in the code and rows in SPEC.md";
  for (size_t i = 0; i < code.size(); ++i) {
    ASSERT_GE(spec[i].size(), 4u) << what << " row " << i;
    const Row& c = code[i];
    const Row& s = spec[i];
    EXPECT_EQ(s[3], c[3]) << what << ": field " << i << " name";
    EXPECT_EQ(s[0], c[0]) << what << "." << c[3] << ": offset";
    EXPECT_EQ(s[1], c[1]) << what << "." << c[3] << ": size";
    if (c[2] == "struct") {
      EXPECT_TRUE(!s[2].empty() && std::isupper(static_cast<unsigned char>(s[2][0])) != 0)
          << what << "." << c[3] << ": type " << s[2] << " is not a struct";
    } else {
      EXPECT_EQ(s[2], c[2]) << what << "." << c[3] << ": type";
    }
  }
}

const std::vector<Row>& message_type_rows() {
  static const std::vector<Row> rows = table_after(spec_lines(), "### 2.2 Message types");
  return rows;
}

// The SPEC name of each defined type ("UpdateChunk"), from §2.2.
std::map<MessageType, std::string> spec_type_names() {
  std::map<MessageType, std::string> names;
  for (const Row& r : message_type_rows()) {
    if (r.size() >= 2) names[static_cast<MessageType>(std::stoul(r[0], nullptr, 16))] = r[1];
  }
  return names;
}

TEST(SpecTables, MessageTypesAreTheDefinedCodesWithTheirNamesAndDirections) {
  const std::vector<Row>& rows = message_type_rows();
  ASSERT_FALSE(rows.empty()) << "SPEC.md §2.2 has no table";
  std::map<int, Row> by_code;
  for (const Row& r : rows) {
    ASSERT_EQ(r.size(), 5u) << r[0];
    ASSERT_EQ(r[0].rfind("0x", 0), 0u) << r[0];
    by_code[static_cast<int>(std::stoul(r[0], nullptr, 16))] = r;
  }
  EXPECT_EQ(by_code.size(), rows.size()) << "a code appears twice";
  for (int code = 0; code < 256; ++code) {
    const auto t = static_cast<MessageType>(code);
    const auto it = by_code.find(code);
    ASSERT_EQ(it != by_code.end(), is_defined(t)) << "type " << code;
    if (it == by_code.end()) continue;
    const Row& r = it->second;
    EXPECT_EQ(snake_case(r[1]), message_name(t)) << r[0];
    const std::string direction = is_request(t) ? "host → board" : is_time_sync(t) ? "sync master → all" : "board → host";
    EXPECT_EQ(r[2], direction) << r[0];
  }
}

// "73" -> [73, 73]; "6 + length (7..262)" -> [7, 262].
std::pair<size_t, size_t> body_size_range(const std::string& cell) {
  const size_t open = cell.find('(');
  if (open == std::string::npos) return {std::stoul(cell), std::stoul(cell)};
  const size_t dots = cell.find("..", open);
  return {std::stoul(cell.substr(open + 1)), std::stoul(cell.substr(dots + 2))};
}

TEST(SpecTables, EveryGoldenMessageHasTheBodySizeOfItsType) {
  std::map<MessageType, std::pair<size_t, size_t>> sizes;
  for (const Row& r : message_type_rows()) {
    if (r.size() >= 4) sizes[static_cast<MessageType>(std::stoul(r[0], nullptr, 16))] = body_size_range(r[3]);
  }
  std::map<MessageType, int> seen;
  for (const auto& [key, message] : golden_messages()) {
    const auto it = sizes.find(message.type());
    ASSERT_NE(it, sizes.end()) << key;
    const size_t body = encode_bytes(message).size() - kMessageHeaderSize;
    EXPECT_GE(body, it->second.first) << key;
    EXPECT_LE(body, it->second.second) << key;
    ++seen[message.type()];
  }
  EXPECT_EQ(seen.size(), sizes.size()) << "types without a golden message";
}

// The field table of each message type (§2.3-2.6) is the code's field list.
template <class T>
class MessageFieldTable : public ::testing::Test {};
using BodyTypeList = ::testing::Types<GetInfo, GetConfig, SetConfig, GetStatus, Identify, PersistConfig, FactoryReset,
                                      Reboot, UpdateBegin, UpdateChunk, UpdateVerify, UpdateAbort, GetLedLog, Sync,
                                      FollowUp, Ack, Info, ConfigReport, StatusReport, LedLog, ErrorResponse>;
struct TypeName {
  template <class T>
  static std::string GetName(int) {
    return message_name(T::kType);
  }
};
TYPED_TEST_SUITE(MessageFieldTable, BodyTypeList, TypeName);

TYPED_TEST(MessageFieldTable, MatchesTheCode) {
  static_assert(std::variant_size_v<Body> == 21, "a new message needs its row in BodyTypeList");
  const std::string name = spec_type_names()[TypeParam::kType];
  ASSERT_FALSE(name.empty());
  const auto lines = spec_lines();
  const std::vector<Row> code = code_rows<TypeParam>();
  const std::vector<Row> spec = table_after(lines, "**" + name + "** (0x");
  if (code.empty()) {
    // Listed among the empty bodies of §2.3, and no table of its own.
    EXPECT_TRUE(spec.empty()) << name << " has a field table but no fields";
    bool listed = false;
    for (size_t i = 0; i + 1 < lines.size(); ++i) {
      const std::string two = lines[i] + " " + lines[i + 1];
      if (two.find("empty body") != std::string::npos && two.find(name + ",") != std::string::npos) listed = true;
      if (two.find("empty body") != std::string::npos && two.find(name + "**") != std::string::npos) listed = true;
    }
    EXPECT_TRUE(listed) << name << " is not listed with an empty body";
    return;
  }
  expect_same_fields(code, spec, name);
}

TEST(SpecTables, NestedFieldTablesMatchTheCode) {
  const auto lines = spec_lines();
  expect_same_fields(code_rows<Config>(), table_after(lines, "### 2.5 Config"), "Config");
  expect_same_fields(code_rows<Code>(), table_after(lines, "**Code** ("), "Code");
  expect_same_fields(code_rows<LedLogEntry>(), table_after(lines, "LedLogEntry ("), "LedLogEntry");
  EXPECT_EQ(detail::encoded_size<Config>(), kConfigSize);
}

TEST(SpecTables, ErrorsAreTheEnumWithItsNames) {
  const std::vector<Row> rows = table_after(spec_lines(), "## 3. Errors");
  ASSERT_FALSE(rows.empty()) << "SPEC.md §3 has no table";
  std::map<int, std::string> by_value;
  for (const Row& r : rows) {
    ASSERT_GE(r.size(), 2u);
    by_value[std::stoi(r[0])] = r[1];
  }
  EXPECT_EQ(by_value.size(), rows.size()) << "a value appears twice";
  const std::string undefined = error_name(static_cast<Error>(255));
  for (int v = 0; v < 256; ++v) {
    const std::string name = error_name(static_cast<Error>(v));
    const auto it = by_value.find(v);
    ASSERT_EQ(it != by_value.end(), name != undefined) << "error " << v << " (" << name << ")";
    if (it != by_value.end()) {
      EXPECT_EQ(it->second, name) << "error " << v;
    }
  }
}

// §4.4: every CAN fault once, with the name and the Error the code gives it.
TEST(SpecTables, CanFaultsAreTheEnumWithTheirErrors) {
  const std::vector<Row> rows = table_after(spec_lines(), "| fault | protocol Error (§3) |");
  ASSERT_EQ(rows.size() + 1, kCanFaultCount) << "SPEC.md §4.4 lists every fault but kNone";
  for (size_t f = 1; f < kCanFaultCount; ++f) {
    const auto fault = static_cast<CanFault>(f);
    const Row& r = rows[f - 1];
    ASSERT_GE(r.size(), 2u);
    EXPECT_EQ(r[0], "`" + std::string(can_fault_name(fault)) + "`") << "fault " << f;
    // `kBadValue` -> bad_value
    const std::string error = r[1].size() > 3 ? snake_case(r[1].substr(2, r[1].size() - 3)) : r[1];
    EXPECT_EQ(error, error_name(can_fault_error(fault))) << can_fault_name(fault);
  }
}

}  // namespace
}  // namespace tetrapulse::protocol::testing
