#include "tetrapulse/datasets/dataset_error.hpp"

#include <fmt/format.h>

namespace tetrapulse {

std::string DatasetError::what() const {
  if (line > 0) return fmt::format("{}:{}: {}", file, line, message);
  return fmt::format("{}: {}", file, message);
}

}  // namespace tetrapulse
