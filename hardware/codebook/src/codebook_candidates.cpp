// Step 1 of the codebook search: the admissible words (SPEC.md §8).
#include <algorithm>

#include "codebook_search.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {
namespace {

// Keeps every offered word while they fit, then a uniform seeded sample of
// them (reservoir sampling, Algorithm R).
class CandidateReservoir {
 public:
  CandidateReservoir(CodebookWorkspace& ws, SplitMix64& rng) : ws_(ws), rng_(rng) {}

  void offer(uint64_t w) {
    if (seen_ < CodebookWorkspace::kMaxCandidates) {
      ws_.words[seen_] = w;
    } else {
      const uint64_t j = rng_.below(seen_ + 1);
      if (j < CodebookWorkspace::kMaxCandidates) ws_.words[j] = w;
    }
    ++seen_;
  }
  uint32_t size() const {
    return seen_ < CodebookWorkspace::kMaxCandidates ? static_cast<uint32_t>(seen_) : CodebookWorkspace::kMaxCandidates;
  }
  bool sampled() const { return seen_ > CodebookWorkspace::kMaxCandidates; }

 private:
  CodebookWorkspace& ws_;
  SplitMix64& rng_;
  uint64_t seen_ = 0;
};

bool admissible(const CodebookSpec& spec, uint64_t w) { return check_code(spec, w, 0).ok(); }

// Every string of length L in lexicographic order.
void enumerate_words(const CodebookSpec& spec, CandidateReservoir& out) {
  const uint32_t L = spec.length;
  const uint64_t end = uint64_t{1} << L;
  for (uint64_t key = 0; key < end; ++key) {
    const uint64_t w = string_order_key(key, L);  // the reversal is its own inverse
    if (admissible(spec, w)) out.offer(w);
  }
}

// Every Lyndon word of length L in lexicographic order (Fredricksen–Kessler–
// Maiorana): the least rotations of the aperiodic words. Periodic words never
// qualify in free-running mode (their shift distance is 0).
void enumerate_lyndon_words(const CodebookSpec& spec, CandidateReservoir& out) {
  const uint32_t L = spec.length;
  uint8_t a[65] = {};  // a[1..L], a[0] unused
  uint32_t i = 1;
  for (;;) {
    if (i == L) {
      uint64_t w = 0;
      for (uint32_t k = 0; k < L; ++k) w |= uint64_t{a[k + 1]} << k;
      if (admissible(spec, w)) out.offer(w);
    }
    i = L;
    while (i > 0 && a[i] == 1) --i;
    if (i == 0) return;
    a[i] = 1;
    for (uint32_t j = i + 1; j <= L; ++j) a[j] = a[j - i];
  }
}

// Seeded random words (least rotations when free-running), kept when admissible.
uint32_t sample_words(const CodebookSpec& spec, CodebookWorkspace& ws, SplitMix64& rng) {
  const uint32_t L = spec.length;
  uint32_t n = 0;
  for (uint32_t draw = 0; draw < kSampleDraws && n < CodebookWorkspace::kMaxCandidates; ++draw) {
    uint64_t w = rng.next() & word_mask(L);
    if (!admissible(spec, w)) continue;  // every constraint is rotation invariant
    if (spec.timing == CodeTiming::kFreeRunning) w = least_rotation(w, L);
    ws.words[n++] = w;
  }
  return n;
}

void sort_in_string_order(uint64_t* words, uint32_t n, uint32_t length) {
  std::sort(words, words + n,
            [length](uint64_t a, uint64_t b) { return string_order_key(a, length) < string_order_key(b, length); });
}

}  // namespace

uint32_t collect_candidates(const CodebookSpec& spec, CodebookWorkspace& ws, SplitMix64& rng, bool* sampled) {
  const uint32_t L = spec.length;
  if (L > kMaxEnumeratedLength) {
    uint32_t n = sample_words(spec, ws, rng);
    sort_in_string_order(ws.words, n, L);
    n = static_cast<uint32_t>(std::unique(ws.words, ws.words + n) - ws.words);
    *sampled = true;
    return n;
  }
  CandidateReservoir reservoir(ws, rng);
  if (spec.timing == CodeTiming::kFreeRunning) {
    enumerate_lyndon_words(spec, reservoir);
  } else {
    enumerate_words(spec, reservoir);
  }
  *sampled = reservoir.sampled();
  if (*sampled) sort_in_string_order(ws.words, reservoir.size(), L);
  return reservoir.size();
}

}  // namespace tetrapulse::protocol
