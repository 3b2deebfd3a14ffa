#pragma once
// The codebook: sets of binary codes that a camera can tell apart (SPEC.md §8).
//
// A code of length L is played cyclically, one bit per bit period; words are
// as in codebook_word.hpp (bit i = character i). A set of codes C is admissible
// for a spec when every code c meets
//   min_weight <= weight(c) <= max_weight,
//   max_cyclic_run(c, 0) <= max_zero_run,  max_cyclic_run(c, 1) <= max_one_run,
//   free-running only:  min_{s=1..L-1} H(c, rot(c, s)) >= d   (phase recoverable),
// and every pair a != b of C is at distance >= d:
//   synchronized:  H(a, b) >= d                      (phase known to the reader),
//   free-running:  min_{s=0..L-1} H(a, rot(b, s)) >= d   (phase unknown).
//
// Freestanding: no heap, no exceptions; the caller owns every buffer.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/protocol/result.hpp"

namespace tetrapulse::protocol {

struct CodebookWorkspace;

// Which kind of code this search makes. Frequency codes (square waves "10",
// "1100", "111000") are chosen differently: codebook_frequency.hpp.
enum class CodeFamily : uint8_t {
  kBinary = 0,  // arbitrary words of one length, chosen by search
};

// Whether the reader knows each frame's bit index.
enum class CodeTiming : uint8_t {
  kSynchronized = 0,  // boards locked to rig time: distance at equal phase
  kFreeRunning = 1,   // phase unknown: distance under every cyclic shift
};

// A run bound that never binds.
constexpr uint8_t kNoRunLimit = 0xFF;

struct CodebookSpec {
  CodeFamily family = CodeFamily::kBinary;
  CodeTiming timing = CodeTiming::kSynchronized;
  uint8_t length = 12;              // L, bits per code, 1..64
  uint8_t min_distance = 3;         // d, 1..L
  uint8_t min_weight = 0;           // fewest 1 bits per code
  uint8_t max_weight = 64;          // most 1 bits per code (>= L: no bound)
  uint8_t max_zero_run = kNoRunLimit;  // longest cyclic run of 0 bits (on_off: LED dark)
  uint8_t max_one_run = kNoRunLimit;   // longest cyclic run of 1 bits
  uint16_t count = 64;              // codes wanted (generate)
  uint64_t seed = 1;                // same spec and seed: same codes, every platform
  uint32_t search_iterations = 20000;  // local-search budget (SPEC.md §8)
};

// What a 0 bit does to an LED (targets.yaml modulation.kind on_off / two_level).
enum class ZeroBit : uint8_t {
  kDark = 0,  // on_off: the marker must stay visible often enough to be tracked
  kDim = 1,   // two_level: always visible
};

// The recommended spec (SPEC.md §8.4) for a timing and modulation; length 0
// picks the recommended length (12 synchronized, 15 free-running). d = 3;
// weights round(0.4 L)..round(0.6 L) synchronized, any free-running; longest
// zero run 2 (synchronized) or 3 (free-running) when a 0 bit is dark, else no
// bound; no bound on runs of ones. Count, seed and budget keep their defaults.
CodebookSpec recommended_spec(CodeTiming timing, ZeroBit zero, uint8_t length = 0);

// What a check found wrong. Faults about one code fill `code`; pair faults fill
// `code` < `other` and the `shift` at which `other` comes closest.
enum class CodebookFault : uint8_t {
  kNone = 0,
  kBadSpec,          // the spec itself is inconsistent (`detail` says how)
  kBitsBeyondLength, // a word has bits set at or above L
  kWeightTooLow,     // value = weight, limit = min_weight
  kWeightTooHigh,    // value = weight, limit = max_weight
  kZeroRunTooLong,   // value = longest cyclic run of 0s, limit = max_zero_run
  kOneRunTooLong,    // value = longest cyclic run of 1s, limit = max_one_run
  kPhaseAmbiguous,   // free-running: value = H(c, rot(c, shift)) < limit = d
  kTooClose,         // value = H(a, rot(b, shift)) < limit = d (shift 0 when synchronized)
};
const char* codebook_fault_name(CodebookFault fault);

struct CodebookReport {
  CodebookFault fault = CodebookFault::kNone;
  uint16_t code = 0;      // index of the offending code (first of a pair)
  uint16_t other = 0;     // second code of a pair
  uint8_t shift = 0;      // rotation of `other` (or of `code` itself) that fails
  uint8_t value = 0;      // the measured weight, run or distance
  uint8_t limit = 0;      // the bound it breaks
  const char* detail = "";  // kBadSpec: which field and why (static text)

  bool ok() const { return fault == CodebookFault::kNone; }
  Status status() const { return ok() ? Status() : Status(Error::kBadValue); }
};

// Whether the spec can be searched or checked at all (kBadSpec or kNone).
CodebookReport check_spec(const CodebookSpec& spec);
// Constraints on one code; `index` is copied into the report.
CodebookReport check_code(const CodebookSpec& spec, uint64_t code, uint16_t index);
// Distance between two codes; indices are copied into the report.
CodebookReport check_pair(const CodebookSpec& spec, uint64_t a, uint16_t index_a, uint64_t b,
                          uint16_t index_b);
// The first fault of a whole set: the spec, then each code in order, then each
// pair (i, j), i < j, in lexicographic order. n <= 65535.
CodebookReport validate(const CodebookSpec& spec, const uint64_t* codes, size_t n);

// What a search did, for reports and benchmarks.
struct CodebookSearchStats {
  uint32_t candidates = 0;       // admissible words the search chose among
  bool candidates_sampled = false;  // true: a seeded sample of them (too many to use all)
  uint32_t iterations = 0;       // local-search iterations run
  bool proven_maximum = false;   // the exact step (at most 64 candidates) proved no larger set exists
};

// Writes min(spec.count, found) codes to out[0..), in string order, and returns
// how many. Fewer than spec.count means the search found no larger set within
// spec.search_iterations; the caller decides whether that is an error.
// Errors: kBadValue (check_spec fails), kNotSupported (family),
// kBufferTooSmall (capacity < spec.count).
Result<size_t> generate(const CodebookSpec& spec, uint64_t* out, size_t capacity, CodebookWorkspace& workspace,
                        CodebookSearchStats* stats = nullptr);

// The largest set the search finds within spec.search_iterations (spec.count is
// ignored), up to `capacity` codes, in string order. A lower bound on the true
// maximum, not a proof of it, except with at most 64 candidates, where an exact
// step decides (stats->proven_maximum).
Result<size_t> find_largest(const CodebookSpec& spec, uint64_t* out, size_t capacity, CodebookWorkspace& workspace,
                            CodebookSearchStats* stats = nullptr);

}  // namespace tetrapulse::protocol
