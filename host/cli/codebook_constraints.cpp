#include "codebook_constraints.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace tetrapulse::cli {

using protocol::CodebookSpec;
using protocol::CodeTiming;
using protocol::kNoRunLimit;

namespace {

std::optional<int> parse_int(const std::string& text) {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (text.empty() || text.size() > 6 || !std::all_of(text.begin(), text.end(), digit)) return std::nullopt;
  return std::stoi(text);
}

tl::expected<uint8_t, CommandLineError> parse_run(const std::string& option, const std::string& text, uint8_t fallback,
                                                  int length) {
  if (text.empty()) return fallback;
  if (text == "none") return kNoRunLimit;
  const std::optional<int> k = parse_int(text);
  if (!k || *k > length) {
    return tl::unexpected(
        CommandLineError{fmt::format("{}: '{}' is not 'none' or a number from 0 to {}", option, text, length)});
  }
  return static_cast<uint8_t>(*k);
}

}  // namespace

void add_codebook_constraint_options(CLI::App* cmd, CodebookConstraintArgs* a) {
  cmd->add_option("--length", a->length, "Bits per code (1-64)")->check(CLI::Range(1, 64));
  cmd->add_option("--distance", a->distance, "Least number of bits in which any two codes differ")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--weights", a->weights, "Ones per code, A-B (e.g. 5-7), or 'any'");
  cmd->add_option("--max-zero-run", a->max_zero_run, "Longest cyclic run of 0 bits (LED dark), or 'none'");
  cmd->add_option("--max-one-run", a->max_one_run, "Longest cyclic run of 1 bits, or 'none'");
}

protocol::ZeroBit zero_bit(ModulationKind modulation) {
  return modulation == ModulationKind::kOnOff ? protocol::ZeroBit::kDark : protocol::ZeroBit::kDim;
}

// The spec for a mode: the recommended one (SPEC.md §8.4), then the options given.
tl::expected<CodebookSpec, CommandLineError> codebook_spec(const CodebookConstraintArgs& a, CodeTiming timing,
                                                           ModulationKind modulation, std::optional<int> file_length) {
  const int given_length = a.length ? *a.length : file_length ? *file_length : 0;
  CodebookSpec s = protocol::recommended_spec(timing, zero_bit(modulation), static_cast<uint8_t>(given_length));
  const int L = s.length;
  if (a.distance) {
    if (*a.distance > L) {
      return tl::unexpected(CommandLineError{fmt::format("--distance: {} exceeds the code length {}", *a.distance, L)});
    }
    s.min_distance = static_cast<uint8_t>(*a.distance);
  }
  if (a.weights == "any") {
    s.min_weight = 0;
    s.max_weight = static_cast<uint8_t>(L);
  } else if (!a.weights.empty()) {
    const size_t dash = a.weights.find('-');
    const std::optional<int> lo = dash == std::string::npos ? std::nullopt : parse_int(a.weights.substr(0, dash));
    const std::optional<int> hi = dash == std::string::npos ? std::nullopt : parse_int(a.weights.substr(dash + 1));
    if (!lo || !hi || *lo > *hi || *hi > L) {
      return tl::unexpected(
          CommandLineError{fmt::format("--weights: '{}' is not 'any' or A-B with 0 <= A <= B <= {}", a.weights, L)});
    }
    s.min_weight = static_cast<uint8_t>(*lo);
    s.max_weight = static_cast<uint8_t>(*hi);
  }
  auto zeros = parse_run("--max-zero-run", a.max_zero_run, s.max_zero_run, L);
  if (!zeros) return tl::unexpected(zeros.error());
  auto ones = parse_run("--max-one-run", a.max_one_run, s.max_one_run, L);
  if (!ones) return tl::unexpected(ones.error());
  s.max_zero_run = *zeros;
  s.max_one_run = *ones;
  s.search_iterations = a.iterations;
  return s;
}
std::string describe_codebook_spec(const CodebookSpec& s) {
  std::string out = fmt::format("{}, {} bits, distance >= {}{}",
                                s.timing == CodeTiming::kFreeRunning ? "free-running" : "synchronized", s.length,
                                s.min_distance, s.timing == CodeTiming::kFreeRunning ? " under every shift" : "");
  if (s.min_weight > 0 || s.max_weight < s.length) out += fmt::format(", weights {}-{}", s.min_weight, s.max_weight);
  if (s.max_zero_run < s.length) out += fmt::format(", zero runs <= {}", s.max_zero_run);
  if (s.max_one_run < s.length) out += fmt::format(", one runs <= {}", s.max_one_run);
  return out;
}

void codebook_error(const std::string& message) { fmt::print(stderr, "tetrapulse codebook: {}\n", message); }

}  // namespace tetrapulse::cli
