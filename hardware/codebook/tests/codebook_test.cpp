// The codebook search and its checks (SPEC.md §8).
#include "tetrapulse/codebook/codebook.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/codebook/codebook_workspace.hpp"

namespace tetrapulse::protocol {
namespace {

CodebookWorkspace& workspace() {
  static const std::unique_ptr<CodebookWorkspace> ws = std::make_unique<CodebookWorkspace>();
  return *ws;
}

std::vector<uint64_t> generated(const CodebookSpec& spec) {
  std::vector<uint64_t> out(spec.count);
  const Result<size_t> n = generate(spec, out.data(), out.size(), workspace());
  EXPECT_TRUE(n.ok()) << error_name(n.error());
  out.resize(n.ok() ? *n : 0);
  return out;
}

std::vector<uint64_t> largest(const CodebookSpec& spec, size_t capacity = 4096) {
  std::vector<uint64_t> out(capacity);
  const Result<size_t> n = find_largest(spec, out.data(), out.size(), workspace());
  EXPECT_TRUE(n.ok()) << error_name(n.error());
  out.resize(n.ok() ? *n : 0);
  return out;
}

// Acceptance: 16 targets x 4 markers, boards synchronized, on_off LEDs.
CodebookSpec synchronized_l12() {
  CodebookSpec s;
  s.timing = CodeTiming::kSynchronized;
  s.length = 12;
  s.min_distance = 3;
  s.min_weight = 5;
  s.max_weight = 7;
  s.max_zero_run = 2;
  s.count = 64;
  return s;
}

// Acceptance: 16 codes for free-running boards.
CodebookSpec free_running_l15() {
  CodebookSpec s;
  s.timing = CodeTiming::kFreeRunning;
  s.length = 15;
  s.min_distance = 3;
  s.max_zero_run = 3;
  s.count = 16;
  return s;
}

std::string describe(const CodebookReport& r) {
  return std::string(codebook_fault_name(r.fault)) + " code " + std::to_string(r.code) + " other " +
         std::to_string(r.other) + " shift " + std::to_string(r.shift) + " value " + std::to_string(r.value) +
         " limit " + std::to_string(r.limit) + " " + r.detail;
}

// The recommended specs are the acceptance specs, and valid for every length.
TEST(Codebook, RecommendedSpecsMeetTheAcceptanceSpecs) {
  for (const CodebookSpec& want : {synchronized_l12(), free_running_l15()}) {
    const CodebookSpec got = recommended_spec(want.timing, ZeroBit::kDark);
    EXPECT_EQ(got.length, want.length);
    EXPECT_EQ(got.min_distance, want.min_distance);
    EXPECT_EQ(got.max_zero_run, want.max_zero_run);
    EXPECT_EQ(got.max_one_run, want.max_one_run);
    if (want.timing == CodeTiming::kSynchronized) {
      EXPECT_EQ(got.min_weight, want.min_weight);
      EXPECT_EQ(got.max_weight, want.max_weight);
    } else {
      EXPECT_EQ(got.min_weight, 0);
      EXPECT_GE(got.max_weight, got.length);
    }
  }
  for (uint8_t L = 1; L <= 64; ++L) {
    for (CodeTiming timing : {CodeTiming::kSynchronized, CodeTiming::kFreeRunning}) {
      for (ZeroBit zero : {ZeroBit::kDark, ZeroBit::kDim}) {
        const CodebookSpec s = recommended_spec(timing, zero, L);
        EXPECT_EQ(s.length, L);
        EXPECT_TRUE(check_spec(s).ok()) << int(L) << " " << check_spec(s).detail;
        EXPECT_EQ(s.max_zero_run == kNoRunLimit, zero == ZeroBit::kDim);
      }
    }
  }
}

TEST(Codebook, SynchronizedTwelveBitsGivesSixtyFourCodes) {
  const CodebookSpec spec = synchronized_l12();
  const std::vector<uint64_t> codes = generated(spec);
  ASSERT_EQ(codes.size(), 64u);
  const CodebookReport r = validate(spec, codes.data(), codes.size());
  EXPECT_TRUE(r.ok()) << describe(r);
}

TEST(Codebook, FreeRunningFifteenBitsGivesSixteenCodes) {
  const CodebookSpec spec = free_running_l15();
  const std::vector<uint64_t> codes = generated(spec);
  ASSERT_EQ(codes.size(), 16u);
  const CodebookReport r = validate(spec, codes.data(), codes.size());
  EXPECT_TRUE(r.ok()) << describe(r);
}

// The local search must find more than the greedy set it starts from
// (search_iterations = 0 stops at the greedy set).
TEST(Codebook, LocalSearchGrowsTheGreedySet) {
  for (CodebookSpec spec : {synchronized_l12(), free_running_l15()}) {
    CodebookSpec greedy = spec;
    greedy.search_iterations = 0;
    const std::vector<uint64_t> start = largest(greedy);
    const std::vector<uint64_t> searched = largest(spec);
    EXPECT_GT(searched.size(), start.size()) << int(spec.length);
    EXPECT_GE(searched.size(), size_t{spec.count});
    const CodebookReport r = validate(spec, searched.data(), searched.size());
    EXPECT_TRUE(r.ok()) << describe(r);
  }
}

// A(n, d), the largest binary codes known to be optimal (Brouwer's tables):
// A(6,3) = 8, A(7,3) = 16 (the Hamming code), A(8,3) = 20, A(9,4) = 20.
TEST(Codebook, ReachesKnownOptimaOfUnconstrainedCodes) {
  struct Case {
    uint8_t length, distance;
    size_t optimum;
  };
  for (const Case c : {Case{6, 3, 8}, Case{7, 3, 16}, Case{8, 3, 20}, Case{9, 4, 20}}) {
    CodebookSpec spec;
    spec.length = c.length;
    spec.min_distance = c.distance;
    spec.search_iterations = 50000;
    const std::vector<uint64_t> codes = largest(spec);
    EXPECT_EQ(codes.size(), c.optimum) << "A(" << int(c.length) << "," << int(c.distance) << ")";
    EXPECT_TRUE(validate(spec, codes.data(), codes.size()).ok());
  }
}

TEST(Codebook, ImpossibleRequestReturnsTheLargestSetFound) {
  CodebookSpec spec;
  spec.length = 6;
  spec.min_distance = 3;
  spec.count = 100;  // A(6,3) = 8
  const std::vector<uint64_t> codes = generated(spec);
  EXPECT_EQ(codes.size(), 8u);
  EXPECT_TRUE(validate(spec, codes.data(), codes.size()).ok());
}

TEST(Codebook, ConstraintsThatNoWordMeetsGiveNoCodes) {
  CodebookSpec spec = synchronized_l12();
  spec.min_weight = 1;
  spec.max_weight = 3;  // at most 3 ones in 12 bits leaves a run of at least 3 zeros
  EXPECT_TRUE(generated(spec).empty());
}

TEST(Codebook, GenerateRejectsBadArguments) {
  uint64_t out[4];
  CodebookSpec spec = synchronized_l12();
  spec.count = 8;
  EXPECT_EQ(generate(spec, out, 4, workspace()).error(), Error::kBufferTooSmall);
  spec.count = 4;
  spec.min_distance = 0;
  EXPECT_EQ(generate(spec, out, 4, workspace()).error(), Error::kBadValue);
  spec.min_distance = 3;
  spec.family = static_cast<CodeFamily>(1);  // frequency codes: not yet
  EXPECT_EQ(generate(spec, out, 4, workspace()).error(), Error::kNotSupported);
}

TEST(CodebookCheck, RejectsABadSpecAndSaysWhichField) {
  CodebookSpec spec = synchronized_l12();
  spec.length = 65;
  CodebookReport r = check_spec(spec);
  EXPECT_EQ(r.fault, CodebookFault::kBadSpec);
  EXPECT_NE(std::string(r.detail).find("length"), std::string::npos);
  spec = synchronized_l12();
  spec.min_distance = 13;
  EXPECT_NE(std::string(check_spec(spec).detail).find("min_distance"), std::string::npos);
  spec = synchronized_l12();
  spec.min_weight = 8;
  EXPECT_NE(std::string(check_spec(spec).detail).find("weight"), std::string::npos);
  EXPECT_EQ(validate(spec, nullptr, 0).fault, CodebookFault::kBadSpec);
}

// Each constraint, broken by one code in a valid set, is reported with the
// code's index, the measured value and the bound.
TEST(CodebookCheck, ReportsEachBrokenConstraintOfOneCode) {
  const CodebookSpec spec = synchronized_l12();
  std::vector<uint64_t> codes = generated(spec);
  ASSERT_EQ(codes.size(), 64u);
  struct Case {
    uint64_t code;
    CodebookFault fault;
    uint8_t value, limit;
  };
  // Bit i is character i: 0b001111111100 is "001111111100".
  const Case cases[] = {
      {0b1011011011011ull, CodebookFault::kBitsBeyondLength, 0, 12},
      {0b000100100011ull, CodebookFault::kWeightTooLow, 4, 5},
      {0b111011011111ull, CodebookFault::kWeightTooHigh, 10, 7},
      {0b110001110101ull, CodebookFault::kZeroRunTooLong, 3, 2},
      {0b001101101100ull, CodebookFault::kZeroRunTooLong, 4, 2},  // the run wraps around
  };
  for (const Case& c : cases) {
    std::vector<uint64_t> bad = codes;
    bad[9] = c.code;
    const CodebookReport r = validate(spec, bad.data(), bad.size());
    EXPECT_EQ(r.fault, c.fault) << describe(r);
    EXPECT_EQ(r.code, 9u);
    EXPECT_EQ(r.value, c.value) << describe(r);
    EXPECT_EQ(r.limit, c.limit);
    EXPECT_FALSE(r.status().ok());
    EXPECT_EQ(r.status().error(), Error::kBadValue);
  }
  CodebookSpec ones = spec;
  ones.max_one_run = 3;
  std::vector<uint64_t> bad = codes;
  bad[9] = 0b011110010011ull;  // "110010011110": a run of four ones
  CodebookReport r = check_code(ones, bad[9], 9);
  EXPECT_EQ(r.fault, CodebookFault::kOneRunTooLong) << describe(r);
  EXPECT_EQ(r.value, max_cyclic_run(bad[9], 12, true));
  EXPECT_EQ(r.limit, 3);
}

TEST(CodebookCheck, ReportsTwoCodesTooCloseWhenSynchronized) {
  const CodebookSpec spec = synchronized_l12();
  std::vector<uint64_t> codes = generated(spec);
  ASSERT_EQ(codes.size(), 64u);
  // Code 17 becomes code 3 with a 1 and a 0 swapped: distance 2, weight kept;
  // the first such swap that keeps the zero runs short.
  uint64_t near = 0;
  for (uint32_t one = 0; one < 12 && near == 0; ++one) {
    for (uint32_t zero = 0; zero < 12 && near == 0; ++zero) {
      const uint64_t w = codes[3] ^ (uint64_t{1} << one) ^ (uint64_t{1} << zero);
      if (((codes[3] >> one) & 1u) && !((codes[3] >> zero) & 1u) && check_code(spec, w, 17).ok()) near = w;
    }
  }
  ASSERT_NE(near, 0u);
  codes[17] = near;
  const CodebookReport r = validate(spec, codes.data(), codes.size());
  EXPECT_EQ(r.fault, CodebookFault::kTooClose) << describe(r);
  EXPECT_EQ(r.code, 3u);
  EXPECT_EQ(r.other, 17u);
  EXPECT_EQ(r.value, 2u);
  EXPECT_EQ(r.limit, 3u);
  EXPECT_EQ(r.shift, 0u);
}

TEST(CodebookCheck, ReportsTheShiftAtWhichFreeRunningCodesCollide) {
  const CodebookSpec spec = free_running_l15();
  std::vector<uint64_t> codes = generated(spec);
  ASSERT_EQ(codes.size(), 16u);
  // Code 11 becomes code 2 read from bit 5, with one bit flipped; read from
  // bit 10 it is code 2 again but for that bit. Every other shift is at least
  // 3 - 1 = 2 away, since code 2 differs from its own shifts in 3 or more bits.
  codes[11] = rotate_word(codes[2], 5, 15) ^ (uint64_t{1} << 7);
  const CodebookReport r = check_pair(spec, codes[2], 2, codes[11], 11);
  ASSERT_EQ(r.fault, CodebookFault::kTooClose) << describe(r);
  EXPECT_EQ(r.code, 2u);
  EXPECT_EQ(r.other, 11u);
  EXPECT_EQ(r.value, 1u);
  EXPECT_EQ(r.limit, 3u);
  EXPECT_EQ(r.shift, 10u);
  EXPECT_EQ(hamming_distance(codes[2], rotate_word(codes[11], r.shift, 15)), r.value);
  // validate() finds it too, unless codes[11] breaks a constraint of its own first.
  const CodebookReport all = validate(spec, codes.data(), codes.size());
  EXPECT_TRUE(all.fault == CodebookFault::kTooClose ? all.code == 2 && all.other == 11 : all.code == 11)
      << describe(all);
}

TEST(CodebookCheck, ReportsACodeWhosePhaseIsAmbiguous) {
  CodebookSpec spec = free_running_l15();
  spec.max_zero_run = kNoRunLimit;
  // "110110110110110" has period 3: it equals itself shifted by 3.
  const uint64_t periodic = 0b011011011011011ull;
  CodebookReport r = check_code(spec, periodic, 4);
  EXPECT_EQ(r.fault, CodebookFault::kPhaseAmbiguous) << describe(r);
  EXPECT_EQ(r.code, 4u);
  EXPECT_EQ(r.value, 0u);
  EXPECT_EQ(r.shift, 3u);
  // Aperiodic, but shift 1 changes only 2 bits: "111111100000000".
  r = check_code(spec, 0b000000001111111ull, 0);
  EXPECT_EQ(r.fault, CodebookFault::kPhaseAmbiguous) << describe(r);
  EXPECT_EQ(r.value, 2u);
  spec.timing = CodeTiming::kSynchronized;  // phase known: no such constraint
  EXPECT_TRUE(check_code(spec, periodic, 4).ok());
}

// --- properties over random specs ---

CodebookSpec random_spec() {
  CodebookSpec s;
  s.timing = *rc::gen::element(CodeTiming::kSynchronized, CodeTiming::kFreeRunning);
  s.length = *rc::gen::inRange<uint8_t>(1, 17);
  s.min_distance = *rc::gen::inRange<uint8_t>(1, static_cast<uint8_t>(std::min(s.length, uint8_t{5}) + 1));
  s.min_weight = *rc::gen::inRange<uint8_t>(0, static_cast<uint8_t>(s.length / 2 + 1));
  s.max_weight = *rc::gen::inRange<uint8_t>(s.min_weight, static_cast<uint8_t>(s.length + 2));
  s.max_zero_run = *rc::gen::element(kNoRunLimit, *rc::gen::inRange<uint8_t>(1, static_cast<uint8_t>(s.length + 1)));
  s.max_one_run = *rc::gen::element(kNoRunLimit, *rc::gen::inRange<uint8_t>(1, static_cast<uint8_t>(s.length + 1)));
  s.count = *rc::gen::inRange<uint16_t>(1, 41);
  s.seed = *rc::gen::arbitrary<uint64_t>();
  s.search_iterations = *rc::gen::inRange<uint32_t>(0, 300);
  return s;
}

RC_GTEST_PROP(CodebookProperty, EveryGeneratedSetPassesValidate, ()) {
  const CodebookSpec spec = random_spec();
  std::vector<uint64_t> out(spec.count);
  const Result<size_t> n = generate(spec, out.data(), out.size(), workspace());
  RC_ASSERT(n.ok());
  RC_ASSERT(*n <= spec.count);
  RC_ASSERT(validate(spec, out.data(), *n).ok());
  for (size_t i = 1; i < *n; ++i) {
    RC_ASSERT(string_order_key(out[i - 1], spec.length) < string_order_key(out[i], spec.length));
  }
}

RC_GTEST_PROP(CodebookProperty, SameSeedSameCodes, ()) {
  const CodebookSpec spec = random_spec();
  std::vector<uint64_t> a(spec.count), b(spec.count);
  CodebookSearchStats sa, sb;
  const Result<size_t> na = generate(spec, a.data(), a.size(), workspace(), &sa);
  // Something else in between, so that no state can leak from one call to the next.
  CodebookSpec other = random_spec();
  std::vector<uint64_t> c(other.count);
  RC_ASSERT(generate(other, c.data(), c.size(), workspace()).ok());
  const Result<size_t> nb = generate(spec, b.data(), b.size(), workspace(), &sb);
  RC_ASSERT(na.ok() && nb.ok());
  RC_ASSERT(*na == *nb);
  RC_ASSERT(std::equal(a.begin(), a.begin() + *na, b.begin()));
  RC_ASSERT(sa.iterations == sb.iterations);
  RC_ASSERT(sa.candidates == sb.candidates);
}

// generate() is find_largest() stopped early on the same path of the search.
RC_GTEST_PROP(CodebookProperty, FindLargestFindsAtLeastAsManyAsGenerate, ()) {
  const CodebookSpec spec = random_spec();
  std::vector<uint64_t> out(spec.count);
  const Result<size_t> n = generate(spec, out.data(), out.size(), workspace());
  const std::vector<uint64_t> most = largest(spec);
  RC_ASSERT(n.ok());
  RC_ASSERT(most.size() >= *n);
  RC_ASSERT(validate(spec, most.data(), most.size()).ok());
}

// The exact maximum by branch and bound, for at most 64 candidates.
class ExactMaximum {
 public:
  explicit ExactMaximum(const CodebookSpec& spec) {
    for (uint64_t w = 0; w <= word_mask(spec.length); ++w) {
      if (!check_code(spec, w, 0).ok()) continue;
      if (spec.timing == CodeTiming::kFreeRunning && least_rotation(w, spec.length) != w) continue;
      words_.push_back(w);
    }
    adjacent_.assign(words_.size(), 0);
    for (size_t i = 0; i < words_.size(); ++i) {
      for (size_t j = 0; j < words_.size(); ++j) {
        if (i != j && !check_pair(spec, words_[i], 0, words_[j], 1).ok()) adjacent_[i] |= uint64_t{1} << j;
      }
    }
  }
  uint32_t solve() {
    best_ = 0;
    const uint64_t all = words_.size() == 64 ? ~uint64_t{0} : (uint64_t{1} << words_.size()) - 1;
    branch(all, 0);
    return best_;
  }

 private:
  void branch(uint64_t open, uint32_t size) {
    if (size + word_weight(open) <= best_) return;
    if (open == 0) {
      best_ = size;
      return;
    }
    const uint32_t v = static_cast<uint32_t>(__builtin_ctzll(open));
    const uint64_t bit = uint64_t{1} << v;
    branch(open & ~bit & ~adjacent_[v], size + 1);
    if (adjacent_[v] & open) branch(open & ~bit, size);  // leaving out an isolated vertex never helps
  }
  std::vector<uint64_t> words_;
  std::vector<uint64_t> adjacent_;
  uint32_t best_ = 0;
};

RC_GTEST_PROP(CodebookProperty, FindsTheExactMaximumOfSmallInstances, ()) {
  CodebookSpec spec = random_spec();
  spec.length = *rc::gen::inRange<uint8_t>(1, 7);
  spec.min_distance = std::min(spec.min_distance, spec.length);
  spec.min_weight = std::min(spec.min_weight, spec.length);
  spec.max_weight = std::max(spec.max_weight, spec.min_weight);
  spec.search_iterations = *rc::gen::inRange<uint32_t>(0, 3000);
  ExactMaximum exact(spec);
  std::vector<uint64_t> most(64);
  CodebookSearchStats stats;
  const Result<size_t> n = find_largest(spec, most.data(), most.size() + 1, workspace(), &stats);
  RC_ASSERT(n.ok());
  RC_ASSERT(*n == exact.solve());
  RC_ASSERT(validate(spec, most.data(), *n).ok());
  RC_ASSERT(stats.proven_maximum == (stats.candidates > 0));
}

// The case that found the local search stalled (CI, rapidcheck): all 26
// odd-weight words are a maximal set no swap leaves; the 30 even-weight words
// are the maximum.
TEST(Codebook, SmallInstancesReachTheMaximumWhereTheLocalSearchStalls) {
  CodebookSpec spec;
  spec.length = 6;
  spec.min_distance = 2;
  spec.min_weight = 1;
  spec.max_weight = 4;
  spec.seed = 1139;
  spec.search_iterations = 3000;
  std::vector<uint64_t> most(64);
  CodebookSearchStats stats;
  const Result<size_t> n = find_largest(spec, most.data(), most.size(), workspace(), &stats);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 30u);
  EXPECT_TRUE(stats.proven_maximum);
  for (size_t i = 0; i < *n; ++i) EXPECT_EQ(word_weight(most[i]) % 2, 0u) << i;
  // generate() takes the same step and stops at the count.
  spec.count = 28;
  std::vector<uint64_t> some(spec.count);
  const Result<size_t> m = generate(spec, some.data(), some.size(), workspace());
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(*m, 28u);
  EXPECT_TRUE(validate(spec, some.data(), *m).ok());
}

// Pins the algorithm (SPEC.md §8): a seed must keep naming the same codebook
// across versions and platforms. Changing the search changes this list; that
// is a protocol change and needs a new codebook version in SPEC.md.
TEST(Codebook, SeedNamesTheSameCodesAcrossVersions) {
  CodebookSpec spec;
  spec.length = 8;
  spec.min_distance = 3;
  spec.count = 20;  // A(8,3): the greedy start is smaller, the local search decides
  spec.seed = 2024;
  const std::vector<uint64_t> codes = generated(spec);
  const std::vector<std::string> pinned = {
      "00000111", "00001001", "00011010", "00110110", "00111101", "01010011", "01011100",
      "01100101", "01101011", "01110000", "10000000", "10001110", "10010101", "10110011",
      "10111000", "11010110", "11011001", "11100010", "11101100", "11111111"};
  std::vector<std::string> got;
  for (uint64_t w : codes) {
    std::string text(8, '0');
    for (uint32_t i = 0; i < 8; ++i) text[i] = ((w >> i) & 1u) ? '1' : '0';
    got.push_back(text);
  }
  EXPECT_EQ(got, pinned);
  CodebookSpec greedy = spec;
  greedy.search_iterations = 0;
  EXPECT_LT(generated(greedy).size(), 20u);  // so the pin covers the local search too
}

}  // namespace
}  // namespace tetrapulse::protocol
