#pragma once
// Working memory of the codebook search (about 4.5 MB), owned by the caller so
// that the codebook library never allocates. A host allocates one and reuses it;
// it holds no state between calls. Its sizes are part of the algorithm
// (SPEC.md §8): at most kMaxCandidates admissible words take part in a search,
// and their conflict graph must fit kMaxNeighbours adjacency entries.
#include <cstddef>
#include <cstdint>

namespace tetrapulse::protocol {

struct CodebookWorkspace {
  static constexpr uint32_t kMaxCandidates = 8192;
  static constexpr uint32_t kMaxNeighbours = uint32_t{1} << 21;
  static constexpr uint32_t kMaxUndo = 4 * kMaxCandidates;

  // Candidate words; vertex v of the conflict graph is words[v].
  uint64_t words[kMaxCandidates];
  // Conflict graph (words closer than d) in compressed rows: the neighbours of
  // v are neighbours[first_neighbour[v] .. first_neighbour[v + 1]).
  uint32_t first_neighbour[kMaxCandidates + 1];
  uint16_t neighbours[kMaxNeighbours];
  // Local-search state.
  uint16_t tight[kMaxCandidates];         // solution neighbours of each vertex
  uint16_t mates[kMaxCandidates];         // xor of their indices (the one, when tight == 1)
  uint16_t solution[kMaxCandidates];      // current independent set
  uint16_t position[kMaxCandidates];      // index of a vertex in `solution`
  uint16_t best[kMaxCandidates];          // largest set seen
  uint16_t saved[kMaxCandidates];         // set before the current perturbation
  uint16_t queue[kMaxCandidates];         // vertices to try a (1,2)-swap on
  uint16_t free_list[kMaxCandidates];     // vertices that may have become free
  uint16_t scratch[kMaxCandidates];       // one-tight neighbours during a swap
  uint16_t undo_log[kMaxUndo];            // this iteration's inserts and removals
  uint8_t in_solution[kMaxCandidates];
  uint8_t queued[kMaxCandidates];
  uint8_t listed_free[kMaxCandidates];
};

}  // namespace tetrapulse::protocol
