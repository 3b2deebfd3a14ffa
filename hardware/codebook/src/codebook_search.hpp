#pragma once
// Internal steps of the codebook search (SPEC.md §8), in the order they run:
// collect admissible words, build their conflict graph, search it for a large
// independent set. Each step draws from the same SplitMix64, so the order of
// draws is part of the algorithm.
#include <cstdint>

#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_random.hpp"
#include "tetrapulse/codebook/codebook_workspace.hpp"

namespace tetrapulse::protocol {

// Words of length L longer than this are sampled, not enumerated.
constexpr uint32_t kMaxEnumeratedLength = 24;
// Random draws when sampling.
constexpr uint32_t kSampleDraws = uint32_t{1} << 22;

// Fills ws.words[0..n) with admissible words (check_code passes; free-running:
// least rotations only), in string order, and returns n. When more than
// kMaxCandidates exist, keeps a seeded sample of them and sets *sampled.
uint32_t collect_candidates(const CodebookSpec& spec, CodebookWorkspace& ws, SplitMix64& rng, bool* sampled);

// True when words a and b may not both be in the set (distance < d).
struct ConflictTest {
  CodeTiming timing;
  uint32_t length;
  uint32_t min_distance;
  bool operator()(uint64_t a, uint64_t b) const;
};

// Goes through ws.words[0..n) in order and keeps each word that conflicts with
// none kept so far, until `target` are kept; their indices go to ws.best[0..returned).
uint32_t greedy_independent_set(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n, uint32_t target);

// Conflict graph of ws.words[0..n) in ws.first_neighbour / ws.neighbours.
// False (graph incomplete) when it needs more than kMaxNeighbours entries.
bool build_conflict_graph(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n);

// Iterated local search for a large independent set of the conflict graph;
// stops once it holds `target` vertices or after `iterations` perturbations.
// Leaves the set in ws.best[0..returned) and the iterations run in *used.
uint32_t search_independent_set(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n, SplitMix64& rng,
                                uint32_t target, uint32_t iterations, uint32_t* used);

// Graphs up to this many vertices are searched exactly after the local search.
constexpr uint32_t kMaxExactVertices = 64;
// Branch-and-bound nodes before the exact step gives up (far above what any
// 64-vertex conflict graph of the search has needed).
constexpr uint64_t kExactNodeBudget = uint64_t{1} << 24;

// When n <= kMaxExactVertices and the local search holds found < target, a
// branch and bound over the graph of ws.first_neighbour / ws.neighbours for
// an independent set of min(maximum, target) vertices; replaces ws.best when
// larger and returns its size (else `found`). *proven: the bound finished
// below the target, so the returned size is the maximum.
uint32_t exact_independent_set(CodebookWorkspace& ws, uint32_t n, uint32_t target, uint32_t found, bool* proven);

}  // namespace tetrapulse::protocol
