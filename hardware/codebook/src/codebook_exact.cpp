// Step 5b of the codebook search (SPEC.md §8): on a conflict graph of at most
// 64 vertices the local search can stall on a maximal set far from the maximum
// (length 6, d = 2, weights 1..4: all 26 odd-weight words, while the 30
// even-weight ones are the maximum, and no swap leads from one to the other),
// so a branch and bound decides exactly. Bound: a greedy clique cover of the
// open vertices; an independent set takes at most one vertex per clique
// (maximum clique in the complement, after Tomita & Seki 2003).
#include "codebook_search.hpp"

namespace tetrapulse::protocol {
namespace {

class ExactSearch {
 public:
  ExactSearch(const uint64_t* adjacent, uint32_t target, uint32_t found, uint64_t budget)
      : adjacent_(adjacent), target_(target), best_size_(found), budget_(budget) {}

  void run(uint64_t open) { branch(open, 0, 0); }
  bool improved() const { return improved_; }
  bool complete() const { return nodes_ <= budget_ && best_size_ < target_; }
  uint32_t size() const { return best_size_; }
  uint64_t set() const { return best_set_; }

 private:
  // Cliques needed to cover `open`: an upper bound on what it still adds.
  uint32_t clique_cover(uint64_t open) const {
    uint32_t cliques = 0;
    while (open) {
      uint64_t candidates = open;
      ++cliques;
      while (candidates) {
        const uint32_t v = static_cast<uint32_t>(__builtin_ctzll(candidates));
        open &= ~(uint64_t{1} << v);
        candidates &= adjacent_[v];
      }
    }
    return cliques;
  }

  void branch(uint64_t open, uint64_t chosen, uint32_t size) {
    if (++nodes_ > budget_ || best_size_ >= target_) return;
    // Vertices with no open neighbour belong to some maximum set: take them all.
    for (uint64_t rest = open; rest;) {
      const uint32_t v = static_cast<uint32_t>(__builtin_ctzll(rest));
      const uint64_t bit = uint64_t{1} << v;
      rest &= ~bit;
      if ((adjacent_[v] & open) == 0) {
        open &= ~bit;
        chosen |= bit;
        ++size;
      }
    }
    if (open == 0) {
      if (size > best_size_) {
        best_size_ = size;
        best_set_ = chosen;
        improved_ = true;
      }
      return;
    }
    if (size + clique_cover(open) <= best_size_) return;
    // Branch on the open vertex with the most open neighbours: leaving it out
    // or taking it removes the most.
    uint32_t pick = 0;
    uint32_t most = 0;
    for (uint64_t rest = open; rest; rest &= rest - 1) {
      const uint32_t v = static_cast<uint32_t>(__builtin_ctzll(rest));
      const uint32_t degree = static_cast<uint32_t>(__builtin_popcountll(adjacent_[v] & open));
      if (degree > most) {
        most = degree;
        pick = v;
      }
    }
    const uint64_t bit = uint64_t{1} << pick;
    branch(open & ~bit & ~adjacent_[pick], chosen | bit, size + 1);
    branch(open & ~bit, chosen, size);
  }

  const uint64_t* adjacent_;
  uint32_t target_;
  uint32_t best_size_;
  uint64_t best_set_ = 0;
  uint64_t budget_;
  uint64_t nodes_ = 0;
  bool improved_ = false;
};

}  // namespace

uint32_t exact_independent_set(CodebookWorkspace& ws, uint32_t n, uint32_t target, uint32_t found, bool* proven) {
  *proven = false;
  if (n == 0 || n > kMaxExactVertices || found >= target) return found;
  uint64_t adjacent[kMaxExactVertices] = {};
  for (uint32_t v = 0; v < n; ++v) {
    for (uint32_t e = ws.first_neighbour[v]; e < ws.first_neighbour[v + 1]; ++e) {
      adjacent[v] |= uint64_t{1} << ws.neighbours[e];
    }
  }
  ExactSearch search(adjacent, target, found, kExactNodeBudget);
  search.run(n == 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1);
  *proven = search.complete();
  if (!search.improved()) return found;
  uint32_t size = 0;
  for (uint64_t rest = search.set(); rest; rest &= rest - 1) {
    ws.best[size++] = static_cast<uint16_t>(__builtin_ctzll(rest));
  }
  return size;
}

}  // namespace tetrapulse::protocol
