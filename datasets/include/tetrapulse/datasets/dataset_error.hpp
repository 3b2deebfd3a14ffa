#pragma once
// An error in a dataset file: which file, which line (0 when not known) and what.
#include <string>

#include <tl/expected.hpp>

namespace tetrapulse {

struct DatasetError {
  std::string file;     // path as given by the caller
  int line = 0;         // 1-based; 0 = the file as a whole
  std::string message;  // what is wrong, naming the field

  // "camera.yaml:12: camera_matrix: expected 9 numbers, got 8"
  std::string what() const;
};

template <typename T>
using DatasetResult = tl::expected<T, DatasetError>;

inline tl::unexpected<DatasetError> dataset_error(std::string file, int line, std::string message) {
  return tl::unexpected<DatasetError>(DatasetError{std::move(file), line, std::move(message)});
}

}  // namespace tetrapulse
