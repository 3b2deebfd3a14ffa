// hardware/board/pinout.md and the firmware's pin table (pinout.hpp) state the same pins,
// so the documentation a person builds from cannot drift from what the firmware drives.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pin_table_reader.hpp"

namespace tetrapulse::board {
namespace {

std::string slurp(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// Replaces the one occurrence of `from`; fails the test if there is not exactly one.
std::string replaced_once(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from << " occurs more than once";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// An input a reader must refuse, and a phrase its error must contain.
struct Refused {
  std::string text;
  std::string says;
};

template <class Reader>
void expect_refused(Reader read, const std::vector<Refused>& cases) {
  for (const Refused& c : cases) {
    const auto t = read(c.text);
    ASSERT_FALSE(t.has_value()) << c.text;
    EXPECT_NE(t.error().find(c.says), std::string::npos) << t.error() << "\nexpected: " << c.says;
  }
}

class PinoutDoc : public ::testing::Test {
 protected:
  std::string header = slurp(TETRAPULSE_PINOUT_HEADER);
  std::string doc = slurp(TETRAPULSE_PINOUT_DOC);

  std::vector<std::string> differences(const std::string& header_text, const std::string& doc_text) {
    auto f = read_firmware_pinout(header_text);
    auto d = read_documented_pinout(doc_text);
    EXPECT_TRUE(f.has_value()) << TETRAPULSE_PINOUT_HEADER << ": " << (f ? "" : f.error());
    EXPECT_TRUE(d.has_value()) << TETRAPULSE_PINOUT_DOC << ": " << (d ? "" : d.error());
    if (!f || !d) return {"unreadable"};
    return pin_table_differences(*f, *d);
  }

  // The one disagreement between the two texts; fails the test when there is not exactly one.
  std::string only_difference(const std::string& header_text, const std::string& doc_text) {
    const auto diff = differences(header_text, doc_text);
    EXPECT_EQ(diff.size(), 1u) << joined(diff);
    return diff.size() == 1 ? diff[0] : joined(diff);
  }
};

TEST_F(PinoutDoc, DocumentedTableAgreesWithFirmwareTable) {
  ASSERT_FALSE(header.empty()) << "cannot read " << TETRAPULSE_PINOUT_HEADER;
  ASSERT_FALSE(doc.empty()) << "cannot read " << TETRAPULSE_PINOUT_DOC;
  const auto diff = differences(header, doc);
  EXPECT_TRUE(diff.empty()) << "pinout.md and pinout.hpp disagree:\n" << joined(diff);
}

TEST_F(PinoutDoc, FirmwareTableCoversEverySignalWithItsPrintedPin) {
  const auto f = read_firmware_pinout(header);
  ASSERT_TRUE(f.has_value()) << f.error();
  // The reader refuses a table that misses an enumerator or misprints a pin; that it
  // accepted the header and found the HSE frequency is what this checks.
  EXPECT_EQ(f->rows.size(), 11u);
  EXPECT_GT(f->hse_hz, 0);
  for (const PinRow& r : f->rows) EXPECT_FALSE(r.function.empty()) << r.signal;
}

// Every field of every documented row matters: change one, and the comparison names
// that signal. This sweeps all rows and all four fields.
TEST_F(PinoutDoc, AnyChangedDocumentedFieldIsReported) {
  const auto d = read_documented_pinout(doc);
  ASSERT_TRUE(d.has_value()) << d.error();
  const auto f = read_firmware_pinout(header);
  ASSERT_TRUE(f.has_value()) << f.error();
  for (size_t i = 0; i < d->rows.size(); ++i) {
    for (int field = 0; field < 4; ++field) {
      PinTable changed = *d;
      PinRow& r = changed.rows[i];
      switch (field) {
        case 0: r.number = (r.number + 1) % 16; break;
        case 1: r.port = r.port == 'A' ? 'B' : 'A'; break;
        case 2: r.alternate = (r.alternate + 1) % 16; break;
        case 3: r.function += "X"; break;
      }
      const auto diff = pin_table_differences(*f, changed);
      ASSERT_EQ(diff.size(), 1u) << r.signal << " field " << field << "\n" << joined(diff);
      EXPECT_EQ(diff[0].rfind(r.signal + ":", 0), 0u) << diff[0];
    }
  }
}

TEST_F(PinoutDoc, MovedPinInTheDocIsReported) {
  const std::string moved = replaced_once(doc, "| `kLed1` | PC7 |", "| `kLed1` | PC10 |");
  EXPECT_EQ(only_difference(header, moved), "kLed1: pin PC7 in firmware, PC10 documented");
}

TEST_F(PinoutDoc, ChangedAlternateFunctionInFirmwareIsReported) {
  const std::string changed = replaced_once(header, "{gpio::Port::kA, 1, 1}", "{gpio::Port::kA, 1, 2}");
  EXPECT_EQ(only_difference(changed, doc), "kSyncInput: AF2 in firmware, AF1 documented");
}

TEST_F(PinoutDoc, RowMissingFromTheDocIsReported) {
  const size_t at = doc.find("| `kCanTx` |");
  ASSERT_NE(at, std::string::npos);
  std::string missing = doc;
  missing.erase(at, doc.find('\n', at) - at + 1);
  EXPECT_EQ(only_difference(header, missing), "kCanTx: on PB9 in firmware, not documented");
}

TEST_F(PinoutDoc, SignalAddedToFirmwareButNotDocumentedIsReported) {
  std::string added = replaced_once(header, "kUsbDm, kUsbDp,", "kUsbDm, kUsbDp, kStatusLed,");
  added = replaced_once(added, "constexpr Pin pin_of",
                        "constexpr PinAssignment kMore[] = {\n"
                        "    {Signal::kStatusLed, {gpio::Port::kB, 0, 0}, \"PB0\", \"GPIO, status LED\"},\n};\n"
                        "constexpr Pin pin_of");
  EXPECT_EQ(only_difference(added, doc), "kStatusLed: on PB0 in firmware, not documented");
}

TEST_F(PinoutDoc, DifferentCrystalIsReported) {
  const std::string changed = replaced_once(header, "kHseHz = 8'000'000", "kHseHz = 12'000'000");
  EXPECT_EQ(only_difference(changed, doc), "HSE: 12000000 Hz in firmware, 8000000 Hz documented");
}

TEST(PinTableReader, RefusesMalformedDocumentation) {
  const std::string head = "| signal (firmware) | pin | LQFP64 | AF | function |\n|---|---|---|---|---|\n";
  const std::string hse = "\nHSE crystal 8 MHz (kHseHz)\n";
  expect_refused(read_documented_pinout, {
      {"no table here\n", "no table whose first column is 'signal (firmware)'"},
      {head + "| kLed0 | PZ6 | 37 | AF3 | TIM8_CH1 |\n" + hse, "pin 'PZ6'"},
      {head + "| kLed0 | PC16 | 37 | AF3 | TIM8_CH1 |\n" + hse, "pin 'PC16'"},
      {head + "| kLed0 | PC6 | 37 | 3 | TIM8_CH1 |\n" + hse, "AF '3'"},
      {head + "| kLed0 | PC6 | 37 | AF16 | TIM8_CH1 |\n" + hse, "AF 'AF16'"},
      {head + "| kLed0 | PC6 | 37 | AF3 |\n" + hse, "4 cells, the header has 5"},
      {head + "| Led0 | PC6 | 37 | AF3 | TIM8_CH1 |\n" + hse, "signal 'Led0'"},
      {head + "| kLed0 | PC6 | 37 | AF3 | TIM8_CH1 |\n| kLed0 | PC7 | 38 | AF3 | TIM8_CH2 |\n" + hse, "kLed0 is listed twice"},
      {head + "| kLed0 | PC6 | 37 | AF3 | TIM8_CH1 |\n", "no line names kHseHz"},
      {head + "| kLed0 | PC6 | 37 | AF3 | TIM8_CH1 |\n\nkHseHz is fast\n", "gives no frequency in MHz"},
      {head + "\n" + hse, "the signal table has no rows"},
  });
}

TEST(PinTableReader, RefusesInconsistentFirmwareTable) {
  const std::string enum_text = "enum class Signal : uint8_t { kA0, kB1 };\n";
  const std::string hse = "constexpr uint32_t kHseHz = 8'000'000;\n";
  const std::string a0 = "{Signal::kA0, {gpio::Port::kA, 0, 1}, \"PA0\", \"TIM2_CH1, x\"},\n";
  const std::string b1 = "{Signal::kB1, {gpio::Port::kB, 1, 2}, \"PB1\", \"TIM3_CH4, y\"},\n";
  expect_refused(read_firmware_pinout, {
      {a0 + b1 + hse, "no 'enum class Signal'"},
      {enum_text + a0 + hse, "Signal::kB1 appears 0 times"},
      {enum_text + a0 + a0 + b1 + hse, "Signal::kA0 appears 2 times"},
      {enum_text + a0 + "{Signal::kB1, {gpio::Port::kB, 1, 2}, \"PB2\", \"TIM3_CH4\"},\n" + hse, "printed \"PB2\" but assigned PB1"},
      {enum_text + a0 + "{Signal::kB1, {gpio::Port::kB, 17, 2}, \"PB17\", \"TIM3_CH4\"},\n" + hse, "not a pin of ports A..I"},
      {enum_text + a0 + "{Signal::kB1, {gpio::Port::kB, 1, 16}, \"PB1\", \"TIM3_CH4\"},\n" + hse, "above AF15"},
      {enum_text + a0 + "{Signal::kB1, {gpio::Port::kB, 1, 2}, \"PB1\", \"timer, y\"},\n" + hse,
       "does not start with its function"},
      {enum_text + a0 + b1, "no kHseHz"},
      // A row commented out does not count.
      {enum_text + a0 + "// " + b1 + hse, "Signal::kB1 appears 0 times"},
  });
  const auto ok = read_firmware_pinout(enum_text + a0 + b1 + hse);
  ASSERT_TRUE(ok.has_value()) << ok.error();
  EXPECT_EQ(ok->rows[1].function, "TIM3_CH4");
  EXPECT_EQ(ok->hse_hz, 8'000'000);
}

}  // namespace
}  // namespace tetrapulse::board
