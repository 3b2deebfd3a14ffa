#pragma once
// A minimal reader for the dataset's CSV files: fixed header, comma-separated
// unquoted fields, one record per line; every error names file and line.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "tetrapulse/datasets/dataset_error.hpp"

namespace tetrapulse::csv {

class Table {
 public:
  // Splits `text` into rows; checks the header equals `header` exactly. A row with
  // the wrong number of fields is an error, or, given `bad_rows`, left out and
  // recorded there (file:line) so the caller can skip it.
  static DatasetResult<Table> parse(const std::string& text, const std::string& file, const std::string& header,
                                    std::vector<DatasetError>* bad_rows = nullptr) {
    Table t;
    t.file_ = file;
    size_t pos = 0;
    int line = 0;
    bool saw_header = false;
    while (pos < text.size()) {
      size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      std::string_view row(text.data() + pos, end - pos);
      pos = end + 1;
      ++line;
      if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
      if (row.empty()) continue;
      if (!saw_header) {
        if (row != header) {
          return dataset_error(file, line, fmt::format("expected header '{}', got '{}'", header, row));
        }
        saw_header = true;
        t.columns_ = split(row).size();
        continue;
      }
      std::vector<std::string_view> fields = split(row);
      if (fields.size() != t.columns_) {
        DatasetError error{file, line, fmt::format("expected {} fields, got {}", t.columns_, fields.size())};
        if (!bad_rows) return tl::unexpected(error);
        bad_rows->push_back(std::move(error));
        continue;
      }
      t.rows_.push_back(Row{line, std::vector<std::string>(fields.begin(), fields.end())});
    }
    if (!saw_header) return dataset_error(file, 0, fmt::format("empty file: expected header '{}'", header));
    return t;
  }

  struct Row {
    int line;
    std::vector<std::string> fields;
  };
  const std::vector<Row>& rows() const { return rows_; }
  const std::string& file() const { return file_; }

 private:
  static std::vector<std::string_view> split(std::string_view row) {
    std::vector<std::string_view> out;
    size_t start = 0;
    while (true) {
      size_t comma = row.find(',', start);
      out.push_back(row.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return out;
  }
  std::string file_;
  size_t columns_ = 0;
  std::vector<Row> rows_;
};

// Field parsers: record the first error (file, line, column name) in `err`.
class FieldReader {
 public:
  FieldReader(const Table& table, const Table::Row& row) : table_(table), row_(row) {}

  int64_t integer(size_t col, const char* name) {
    const std::string& s = row_.fields[col];
    int64_t v = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || s.empty()) fail(name, s, "an integer");
    return v;
  }
  double number(size_t col, const char* name) {
    const std::string& s = row_.fields[col];
    double v = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || s.empty() || !std::isfinite(v)) fail(name, s, "a finite number");
    return v;
  }
  const std::string& text(size_t col) const { return row_.fields[col]; }
  void fail(const std::string& message) {
    if (!error_) error_ = DatasetError{table_.file(), row_.line, message};
  }
  bool failed() const { return error_.has_value(); }
  const DatasetError& error() const { return *error_; }
  int line() const { return row_.line; }

 private:
  void fail(const char* name, const std::string& got, const char* what) {
    fail(fmt::format("{}: expected {}, got '{}'", name, what, got));
  }
  const Table& table_;
  const Table::Row& row_;
  std::optional<DatasetError> error_;
};

}  // namespace tetrapulse::csv
