#include "pin_table_reader.hpp"

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace tetrapulse::board {
namespace {

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const size_t end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

// A Markdown cell without surrounding spaces and code backticks.
std::string cell_text(const std::string& cell) {
  std::string t = trim(cell);
  t.erase(std::remove(t.begin(), t.end(), '`'), t.end());
  return trim(t);
}

std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string t = trim(line);
  if (t.size() < 2 || t.front() != '|') return cells;
  t = t.substr(1);
  if (!t.empty() && t.back() == '|') t.pop_back();
  std::stringstream in(t);
  std::string cell;
  while (std::getline(in, cell, '|')) cells.push_back(cell_text(cell));
  return cells;
}

std::string without_line_comments(const std::string& text) {
  return std::regex_replace(text, std::regex("//[^\n]*"), "");
}

std::string pin_name(char port, int number) { return std::string("P") + port + std::to_string(number); }

bool valid_pin(char port, int number) { return port >= 'A' && port <= 'I' && number >= 0 && number <= 15; }

// "PC6" -> ('C', 6); false when the text is not a pin name.
bool parse_pin(const std::string& text, char* port, int* number) {
  std::smatch m;
  static const std::regex pattern("^P([A-Z])([0-9]{1,2})$");
  if (!std::regex_match(text, m, pattern)) return false;
  *port = m[1].str()[0];
  *number = std::stoi(m[2].str());
  return valid_pin(*port, *number);
}

// The peripheral function that a role string starts with: "USART1_RX (pull-up)" -> "USART1_RX".
std::string leading_function(const std::string& role) {
  std::smatch m;
  return std::regex_search(role, m, std::regex("^\\s*([A-Z][A-Z0-9_]*)")) ? m[1].str() : std::string();
}

tl::expected<std::vector<std::string>, std::string> signal_names(const std::string& code) {
  std::smatch m;
  if (!std::regex_search(code, m, std::regex("enum\\s+class\\s+Signal[^{]*\\{([^}]*)\\}"))) {
    return tl::make_unexpected(std::string("no 'enum class Signal' in the header"));
  }
  const std::string body = m[1].str();
  std::vector<std::string> names;
  const std::regex name("\\bk[A-Z][A-Za-z0-9_]*");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), name); it != std::sregex_iterator(); ++it) {
    names.push_back(it->str());
  }
  if (names.empty()) return tl::make_unexpected(std::string("'enum class Signal' has no enumerators"));
  return names;
}

}  // namespace

tl::expected<PinTable, std::string> read_firmware_pinout(const std::string& header_text) {
  const std::string code = without_line_comments(header_text);
  auto names = signal_names(code);
  if (!names) return tl::make_unexpected(names.error());

  PinTable table;
  const std::regex row(
      "\\{\\s*Signal::(\\w+)\\s*,\\s*\\{\\s*gpio::Port::k([A-Z])\\s*,\\s*([0-9]+)\\s*,\\s*([0-9]+)\\s*\\}\\s*,"
      "\\s*\"([^\"]*)\"\\s*,\\s*\"([^\"]*)\"\\s*\\}");
  for (auto it = std::sregex_iterator(code.begin(), code.end(), row); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    PinRow r;
    r.signal = m[1].str();
    r.port = m[2].str()[0];
    r.number = std::stoi(m[3].str());
    r.alternate = std::stoi(m[4].str());
    r.function = leading_function(m[6].str());
    if (!valid_pin(r.port, r.number)) {
      return tl::make_unexpected("kPinout: " + r.signal + " is on " + pin_name(r.port, r.number) + ", not a pin of ports A..I");
    }
    if (m[5].str() != pin_name(r.port, r.number)) {
      return tl::make_unexpected("kPinout: " + r.signal + " is printed \"" + m[5].str() + "\" but assigned " +
                                 pin_name(r.port, r.number));
    }
    if (r.function.empty()) {
      return tl::make_unexpected("kPinout: " + r.signal + "'s role \"" + m[6].str() + "\" does not start with its function");
    }
    if (r.alternate > 15) return tl::make_unexpected("kPinout: " + r.signal + " has AF" + m[4].str() + ", above AF15");
    table.rows.push_back(r);
  }
  for (const std::string& name : *names) {
    const auto count = std::count_if(table.rows.begin(), table.rows.end(), [&](const PinRow& r) { return r.signal == name; });
    if (count != 1) {
      return tl::make_unexpected("kPinout: Signal::" + name + " appears " + std::to_string(count) + " times (expected once)");
    }
  }
  if (table.rows.size() != names->size()) {
    return tl::make_unexpected("kPinout: " + std::to_string(table.rows.size()) + " rows for " +
                               std::to_string(names->size()) + " Signal enumerators");
  }

  std::smatch hse;
  if (!std::regex_search(code, hse, std::regex("kHseHz\\s*=\\s*([0-9']+)"))) {
    return tl::make_unexpected(std::string("no kHseHz in the header"));
  }
  std::string digits = hse[1].str();
  digits.erase(std::remove(digits.begin(), digits.end(), '\''), digits.end());
  table.hse_hz = std::stol(digits);
  return table;
}

tl::expected<PinTable, std::string> read_documented_pinout(const std::string& markdown_text) {
  std::vector<std::string> lines;
  {
    std::stringstream in(markdown_text);
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
  }

  size_t header = lines.size();
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto cells = table_cells(lines[i]);
    if (!cells.empty() && cells[0] == "signal (firmware)") {
      header = i;
      break;
    }
  }
  if (header == lines.size()) {
    return tl::make_unexpected(std::string("no table whose first column is 'signal (firmware)'"));
  }
  const auto columns = table_cells(lines[header]);
  auto column = [&](const std::string& name) -> long {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<long>(it - columns.begin());
  };
  const long pin_col = column("pin"), af_col = column("AF"), function_col = column("function");
  if (pin_col < 0 || af_col < 0 || function_col < 0) {
    return tl::make_unexpected("line " + std::to_string(header + 1) + ": the signal table needs columns 'pin', 'AF' and 'function'");
  }

  PinTable table;
  std::set<std::string> seen;
  for (size_t i = header + 2; i < lines.size(); ++i) {
    const auto cells = table_cells(lines[i]);
    if (cells.empty()) break;
    const std::string where = "line " + std::to_string(i + 1) + ": ";
    if (cells.size() != columns.size()) {
      return tl::make_unexpected(where + std::to_string(cells.size()) + " cells, the header has " + std::to_string(columns.size()));
    }
    PinRow r;
    r.signal = cells[0];
    if (!std::regex_match(r.signal, std::regex("k[A-Z][A-Za-z0-9_]*"))) {
      return tl::make_unexpected(where + "signal '" + r.signal + "' is not a firmware Signal name (kName)");
    }
    if (!seen.insert(r.signal).second) return tl::make_unexpected(where + r.signal + " is listed twice");
    if (!parse_pin(cells[pin_col], &r.port, &r.number)) {
      return tl::make_unexpected(where + "pin '" + cells[pin_col] + "' is not P<port A..I><0..15>");
    }
    std::smatch af;
    if (!std::regex_match(cells[af_col], af, std::regex("AF([0-9]{1,2})")) || std::stoi(af[1].str()) > 15) {
      return tl::make_unexpected(where + "AF '" + cells[af_col] + "' is not AF0..AF15");
    }
    r.alternate = std::stoi(af[1].str());
    r.function = cells[function_col];
    table.rows.push_back(r);
  }
  if (table.rows.empty()) return tl::make_unexpected(std::string("the signal table has no rows"));

  for (const std::string& line : lines) {
    if (line.find("kHseHz") == std::string::npos) continue;
    std::smatch mhz;
    if (!std::regex_search(line, mhz, std::regex("([0-9]+(\\.[0-9]+)?)\\s*MHz"))) {
      return tl::make_unexpected(std::string("the line naming kHseHz gives no frequency in MHz"));
    }
    table.hse_hz = static_cast<long>(std::stod(mhz[1].str()) * 1e6 + 0.5);
    return table;
  }
  return tl::make_unexpected(std::string("no line names kHseHz (the HSE crystal frequency)"));
}

std::vector<std::string> pin_table_differences(const PinTable& firmware, const PinTable& documented) {
  std::vector<std::string> out;
  std::map<std::string, const PinRow*> doc;
  for (const PinRow& r : documented.rows) doc[r.signal] = &r;

  for (const PinRow& f : firmware.rows) {
    const auto it = doc.find(f.signal);
    if (it == doc.end()) {
      out.push_back(f.signal + ": on " + pin_name(f.port, f.number) + " in firmware, not documented");
      continue;
    }
    const PinRow& d = *it->second;
    if (f.port != d.port || f.number != d.number) {
      out.push_back(f.signal + ": pin " + pin_name(f.port, f.number) + " in firmware, " + pin_name(d.port, d.number) +
                    " documented");
    }
    if (f.alternate != d.alternate) {
      out.push_back(f.signal + ": AF" + std::to_string(f.alternate) + " in firmware, AF" + std::to_string(d.alternate) +
                    " documented");
    }
    if (f.function != d.function) {
      out.push_back(f.signal + ": function " + f.function + " in firmware, " + d.function + " documented");
    }
    doc.erase(it);
  }
  for (const auto& [signal, row] : doc) {
    out.push_back(signal + ": documented on " + pin_name(row->port, row->number) + ", not in the firmware table");
  }
  if (firmware.hse_hz != documented.hse_hz) {
    out.push_back("HSE: " + std::to_string(firmware.hse_hz) + " Hz in firmware, " + std::to_string(documented.hse_hz) +
                  " Hz documented");
  }
  return out;
}

}  // namespace tetrapulse::board
