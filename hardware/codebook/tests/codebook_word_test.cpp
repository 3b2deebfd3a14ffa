// Word measures checked against a plain string reference (character i = bit i).
#include "tetrapulse/codebook/codebook_word.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <string>

#include "tetrapulse/codebook/codebook_random.hpp"

namespace tetrapulse::protocol {
namespace {

std::string text(uint64_t w, uint32_t L) {
  std::string s(L, '0');
  for (uint32_t i = 0; i < L; ++i) s[i] = ((w >> i) & 1u) ? '1' : '0';
  return s;
}

// Character i of the result is character (i + k) mod L of s.
std::string rotated(const std::string& s, size_t k) { return s.substr(k) + s.substr(0, k); }

uint32_t differing(const std::string& a, const std::string& b) {
  uint32_t d = 0;
  for (size_t i = 0; i < a.size(); ++i) d += a[i] != b[i];
  return d;
}

// min over k = first..L-1 of differing(a, rotated(b, k)), with the first k reaching it.
ShiftDistance fewest_differences_over_shifts(const std::string& a, const std::string& b, uint32_t first) {
  ShiftDistance best{static_cast<uint32_t>(a.size()) + 1, 0};
  for (uint32_t k = first; k < a.size(); ++k) {
    const uint32_t d = differing(a, rotated(b, k));
    if (d < best.distance) best = ShiftDistance{d, k};
  }
  return best;
}

uint32_t longest_cyclic_run(const std::string& s, char c) {
  if (std::count(s.begin(), s.end(), c) == static_cast<long>(s.size())) return static_cast<uint32_t>(s.size());
  const std::string twice = s + s;
  uint32_t best = 0, run = 0;
  for (char x : twice) {
    run = x == c ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

struct Word {
  uint64_t bits;
  uint32_t length;
};

rc::Gen<Word> words() {
  return rc::gen::mapcat(rc::gen::inRange<uint32_t>(1, 65), [](uint32_t L) {
    return rc::gen::map(rc::gen::arbitrary<uint64_t>(), [L](uint64_t w) { return Word{w & word_mask(L), L}; });
  });
}

// Words with long runs and near-periodic structure, which uniform words rarely have.
uint64_t structured(uint64_t seed, uint32_t L) {
  SplitMix64 rng(seed);
  const uint32_t period = 1 + static_cast<uint32_t>(rng.below(L));
  const uint64_t pattern = rng.next();
  uint64_t w = 0;
  for (uint32_t i = 0; i < L; ++i) w |= ((pattern >> (i % period)) & 1u) << i;
  if (rng.below(2) == 0) w ^= uint64_t{1} << rng.below(L);
  return w & word_mask(L);
}

RC_GTEST_PROP(CodebookWord, RotateReadsFromTheShift, ()) {
  const Word w = *words();
  const uint32_t s = *rc::gen::inRange<uint32_t>(0, w.length);
  RC_ASSERT(text(rotate_word(w.bits, s, w.length), w.length) == rotated(text(w.bits, w.length), s));
}

RC_GTEST_PROP(CodebookWord, WeightAndRunsMatchTheReference, ()) {
  const Word w = *words();
  const uint64_t bits = *rc::gen::element(w.bits, structured(w.bits, w.length));
  const std::string s = text(bits, w.length);
  RC_ASSERT(word_weight(bits) == static_cast<uint32_t>(std::count(s.begin(), s.end(), '1')));
  RC_ASSERT(max_cyclic_run(bits, w.length, false) == longest_cyclic_run(s, '0'));
  RC_ASSERT(max_cyclic_run(bits, w.length, true) == longest_cyclic_run(s, '1'));
}

RC_GTEST_PROP(CodebookWord, CyclicDistanceIsTheMinimumOverShifts, ()) {
  const Word a = *words();
  const uint64_t b = *rc::gen::oneOf(
      rc::gen::map(rc::gen::arbitrary<uint64_t>(), [&](uint64_t x) { return x & word_mask(a.length); }),
      // b close to a rotation of a, where the minimum is small and the shift matters
      rc::gen::map(rc::gen::arbitrary<uint64_t>(), [&](uint64_t x) {
        return rotate_word(a.bits, static_cast<uint32_t>(x % a.length), a.length) ^
               (uint64_t{1} << ((x >> 8) % a.length));
      }));
  const ShiftDistance want = fewest_differences_over_shifts(text(a.bits, a.length), text(b, a.length), 0);
  const ShiftDistance got = cyclic_distance(a.bits, b, a.length);
  RC_ASSERT(got.distance == want.distance);
  RC_ASSERT(got.shift == want.shift);
  for (uint32_t d = 1; d <= a.length; ++d) {
    RC_ASSERT(cyclically_closer_than(a.bits, b, a.length, d) == (want.distance < d));
  }
  RC_ASSERT(cyclic_distance(b, a.bits, a.length).distance == want.distance);  // symmetric
}

RC_GTEST_PROP(CodebookWord, SelfShiftDistanceIsTheMinimumOverNonTrivialShifts, ()) {
  const Word w = *words();
  const uint64_t bits = *rc::gen::element(w.bits, structured(w.bits, w.length));
  const std::string s = text(bits, w.length);
  const ShiftDistance got = self_shift_distance(bits, w.length);
  if (w.length == 1) {
    RC_ASSERT(got.distance == 1u);
    return;
  }
  const ShiftDistance want = fewest_differences_over_shifts(s, s, 1);
  RC_ASSERT(got.distance == want.distance);
  RC_ASSERT(got.shift == want.shift);
}

RC_GTEST_PROP(CodebookWord, LeastPeriodIsTheSmallestShiftThatRepeats, ()) {
  const Word w = *words();
  const uint64_t bits = *rc::gen::element(w.bits, structured(w.bits, w.length));
  const std::string s = text(bits, w.length);
  uint32_t want = w.length;
  for (uint32_t k = w.length - 1; k >= 1; --k) {
    if (rotated(s, k) == s) want = k;
  }
  RC_ASSERT(least_period(bits, w.length) == want);
}

RC_GTEST_PROP(CodebookWord, StringOrderKeyOrdersLikeTheStrings, ()) {
  const Word a = *words();
  const uint64_t b = *rc::gen::arbitrary<uint64_t>() & word_mask(a.length);
  const std::string sa = text(a.bits, a.length), sb = text(b, a.length);
  RC_ASSERT((string_order_key(a.bits, a.length) < string_order_key(b, a.length)) == (sa < sb));
  RC_ASSERT(string_order_key(string_order_key(a.bits, a.length), a.length) == a.bits);
}

RC_GTEST_PROP(CodebookWord, LeastRotationIsTheSmallestRotatedString, ()) {
  const Word w = *words();
  const uint64_t bits = *rc::gen::element(w.bits, structured(w.bits, w.length));
  const std::string s = text(bits, w.length);
  std::string least = s;
  for (uint32_t k = 1; k < w.length; ++k) least = std::min(least, rotated(s, k));
  RC_ASSERT(text(least_rotation(bits, w.length), w.length) == least);
}

TEST(CodebookWord, RunsWrapAroundTheEnd) {
  // "001111111100": two zeros at each end make one cyclic run of four.
  const uint64_t w = 0b001111111100;  // bit 0 is the first character
  EXPECT_EQ(text(w, 12), "001111111100");
  EXPECT_EQ(max_cyclic_run(w, 12, false), 4u);
  EXPECT_EQ(max_cyclic_run(w, 12, true), 8u);
  EXPECT_EQ(max_cyclic_run(0, 12, false), 12u);
  EXPECT_EQ(max_cyclic_run(0, 12, true), 0u);
  EXPECT_EQ(max_cyclic_run(~uint64_t{0}, 64, true), 64u);
}

TEST(CodebookWord, PeriodicWordsHaveShiftDistanceZero) {
  EXPECT_EQ(self_shift_distance(0b101010101010, 12).distance, 0u);
  EXPECT_EQ(self_shift_distance(0b101010101010, 12).shift, 2u);
  EXPECT_EQ(self_shift_distance(0b011011011011, 12).shift, 3u);
  EXPECT_EQ(least_period(0b011011011011, 12), 3u);
  EXPECT_EQ(least_period(0b011011011010, 12), 12u);
}

// SplitMix64's published first outputs for seed 0 (Vigna's reference code):
// the codebook's reproducibility rests on this sequence.
TEST(SplitMix64, MatchesTheReferenceSequence) {
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(rng.next(), 0x06C45D188009454Full);
}

TEST(SplitMix64, BelowStaysInRangeAndCoversIt) {
  SplitMix64 rng(7);
  for (uint64_t n : {1ull, 2ull, 3ull, 7ull, 1000ull, (1ull << 63) + 5}) {
    bool saw_last = false, saw_first = false;
    for (int i = 0; i < 5000; ++i) {
      const uint64_t r = rng.below(n);
      ASSERT_LT(r, n);
      saw_first |= r == 0;
      saw_last |= r == n - 1;
    }
    if (n <= 1000) {
      EXPECT_TRUE(saw_first) << n;
      EXPECT_TRUE(saw_last) << n;
    }
  }
}

TEST(SplitMix64, ShuffleIsAPermutationAndDependsOnTheSeed) {
  uint32_t a[50], b[50];
  for (uint32_t i = 0; i < 50; ++i) a[i] = b[i] = i;
  SplitMix64 ra(1), rb(2);
  ra.shuffle(a, 50);
  rb.shuffle(b, 50);
  uint32_t sorted[50];
  std::copy(a, a + 50, sorted);
  std::sort(sorted, sorted + 50);
  for (uint32_t i = 0; i < 50; ++i) EXPECT_EQ(sorted[i], i);
  EXPECT_FALSE(std::equal(a, a + 50, b));
}

}  // namespace
}  // namespace tetrapulse::protocol
