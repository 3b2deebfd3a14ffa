// generate() and find_largest(): the codebook search end to end (SPEC.md §8).
#include "tetrapulse/codebook/codebook.hpp"

#include <algorithm>

#include "codebook_search.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {
namespace {

// Runs the search until it holds `target` codes or its budget is spent, and
// writes up to `limit` of the best set to out[] in string order.
Result<size_t> search(const CodebookSpec& spec, uint32_t target, size_t limit, uint64_t* out, CodebookWorkspace& ws,
                      CodebookSearchStats* stats) {
  if (spec.family != CodeFamily::kBinary) return Error::kNotSupported;
  if (!check_spec(spec).ok()) return Error::kBadValue;
  SplitMix64 rng(spec.seed);
  CodebookSearchStats local;
  CodebookSearchStats& s = stats ? *stats : local;
  s = CodebookSearchStats{};
  if (target == 0) return size_t{0};

  uint32_t n = collect_candidates(spec, ws, rng, &s.candidates_sampled);
  rng.shuffle(ws.words, n);
  const ConflictTest conflict{spec.timing, spec.length, spec.min_distance};
  s.candidates = n;
  // The greedy set is where the local search would start; often it is enough.
  uint32_t found = greedy_independent_set(conflict, ws, n, target);
  if (found < target) {
    // Too dense a graph for the workspace: keep the first half of the shuffled words.
    while (!build_conflict_graph(conflict, ws, n)) {
      n /= 2;
      s.candidates = n;
      s.candidates_sampled = true;
    }
    found = search_independent_set(conflict, ws, n, rng, target, spec.search_iterations, &s.iterations);
    found = exact_independent_set(ws, n, target, found, &s.proven_maximum);
  }

  const uint32_t L = spec.length;
  std::sort(ws.best, ws.best + found, [&ws, L](uint16_t a, uint16_t b) {
    return string_order_key(ws.words[a], L) < string_order_key(ws.words[b], L);
  });
  const size_t written = std::min<size_t>(found, limit);
  for (size_t i = 0; i < written; ++i) out[i] = ws.words[ws.best[i]];
  return written;
}

}  // namespace

CodebookSpec recommended_spec(CodeTiming timing, ZeroBit zero, uint8_t length) {
  const bool free = timing == CodeTiming::kFreeRunning;
  CodebookSpec s;
  s.timing = timing;
  s.length = length > 0 ? length : free ? 15 : 12;
  s.min_distance = s.length < 3 ? s.length : 3;
  // Balanced codes keep every marker about equally bright on average.
  s.min_weight = static_cast<uint8_t>(free ? 0 : (4 * s.length + 5) / 10);
  s.max_weight = static_cast<uint8_t>(free ? s.length : (6 * s.length + 5) / 10);
  s.max_zero_run = zero == ZeroBit::kDark ? (free ? 3 : 2) : kNoRunLimit;
  s.max_one_run = kNoRunLimit;
  return s;
}

Result<size_t> generate(const CodebookSpec& spec, uint64_t* out, size_t capacity, CodebookWorkspace& workspace,
                        CodebookSearchStats* stats) {
  if (capacity < spec.count) return Error::kBufferTooSmall;
  return search(spec, spec.count, spec.count, out, workspace, stats);
}

Result<size_t> find_largest(const CodebookSpec& spec, uint64_t* out, size_t capacity, CodebookWorkspace& workspace,
                            CodebookSearchStats* stats) {
  const uint32_t target = capacity < CodebookWorkspace::kMaxCandidates ? static_cast<uint32_t>(capacity)
                                                                       : CodebookWorkspace::kMaxCandidates;
  return search(spec, target, capacity, out, workspace, stats);
}

}  // namespace tetrapulse::protocol
