// Checks of a spec, a code and a pair of codes against SPEC.md §8.
#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {
namespace {

CodebookReport bad_spec(const char* detail) {
  CodebookReport r;
  r.fault = CodebookFault::kBadSpec;
  r.detail = detail;
  return r;
}

CodebookReport code_fault(CodebookFault fault, uint16_t index, uint32_t value, uint32_t limit, uint32_t shift = 0) {
  CodebookReport r;
  r.fault = fault;
  r.code = index;
  r.other = index;
  r.value = static_cast<uint8_t>(value);
  r.limit = static_cast<uint8_t>(limit);
  r.shift = static_cast<uint8_t>(shift);
  return r;
}

}  // namespace

const char* codebook_fault_name(CodebookFault fault) {
  switch (fault) {
    case CodebookFault::kNone: return "none";
    case CodebookFault::kBadSpec: return "bad_spec";
    case CodebookFault::kBitsBeyondLength: return "bits_beyond_length";
    case CodebookFault::kWeightTooLow: return "weight_too_low";
    case CodebookFault::kWeightTooHigh: return "weight_too_high";
    case CodebookFault::kZeroRunTooLong: return "zero_run_too_long";
    case CodebookFault::kOneRunTooLong: return "one_run_too_long";
    case CodebookFault::kPhaseAmbiguous: return "phase_ambiguous";
    case CodebookFault::kTooClose: return "too_close";
  }
  return "unknown_fault";
}

CodebookReport check_spec(const CodebookSpec& spec) {
  if (spec.family != CodeFamily::kBinary) return bad_spec("family: only binary codes are defined");
  if (spec.timing != CodeTiming::kSynchronized && spec.timing != CodeTiming::kFreeRunning) {
    return bad_spec("timing: neither synchronized nor free-running");
  }
  if (spec.length < 1 || spec.length > 64) return bad_spec("length: must be 1..64 bits");
  if (spec.min_distance < 1 || spec.min_distance > spec.length) {
    return bad_spec("min_distance: must be 1..length");
  }
  if (spec.min_weight > spec.length) return bad_spec("min_weight: exceeds the length");
  if (spec.min_weight > spec.max_weight) return bad_spec("weights: min_weight exceeds max_weight");
  return CodebookReport{};
}

CodebookReport check_code(const CodebookSpec& spec, uint64_t code, uint16_t index) {
  const uint32_t L = spec.length;
  if ((code & ~word_mask(L)) != 0) return code_fault(CodebookFault::kBitsBeyondLength, index, 0, L);
  const uint32_t weight = word_weight(code);
  if (weight < spec.min_weight) return code_fault(CodebookFault::kWeightTooLow, index, weight, spec.min_weight);
  if (weight > spec.max_weight) return code_fault(CodebookFault::kWeightTooHigh, index, weight, spec.max_weight);
  const uint32_t zeros = max_cyclic_run(code, L, false);
  if (zeros > spec.max_zero_run) return code_fault(CodebookFault::kZeroRunTooLong, index, zeros, spec.max_zero_run);
  const uint32_t ones = max_cyclic_run(code, L, true);
  if (ones > spec.max_one_run) return code_fault(CodebookFault::kOneRunTooLong, index, ones, spec.max_one_run);
  if (spec.timing == CodeTiming::kFreeRunning) {
    const ShiftDistance self = self_shift_distance(code, L);
    if (self.distance < spec.min_distance) {
      return code_fault(CodebookFault::kPhaseAmbiguous, index, self.distance, spec.min_distance, self.shift);
    }
  }
  return CodebookReport{};
}

CodebookReport check_pair(const CodebookSpec& spec, uint64_t a, uint16_t index_a, uint64_t b, uint16_t index_b) {
  const ShiftDistance d = spec.timing == CodeTiming::kFreeRunning
                              ? cyclic_distance(a, b, spec.length)
                              : ShiftDistance{hamming_distance(a, b), 0};
  if (d.distance >= spec.min_distance) return CodebookReport{};
  CodebookReport r = code_fault(CodebookFault::kTooClose, index_a, d.distance, spec.min_distance, d.shift);
  r.other = index_b;
  return r;
}

CodebookReport validate(const CodebookSpec& spec, const uint64_t* codes, size_t n) {
  CodebookReport r = check_spec(spec);
  if (!r.ok()) return r;
  if (n > 0xFFFF) return bad_spec("count: more than 65535 codes");
  for (size_t i = 0; i < n; ++i) {
    r = check_code(spec, codes[i], static_cast<uint16_t>(i));
    if (!r.ok()) return r;
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      r = check_pair(spec, codes[i], static_cast<uint16_t>(i), codes[j], static_cast<uint16_t>(j));
      if (!r.ok()) return r;
    }
  }
  return r;
}

}  // namespace tetrapulse::protocol
