// Steps 2 and 3 of the codebook search (SPEC.md §8): the conflict graph of the
// candidate words, and a large independent set in it by iterated local search
// with (1,2)-swaps, after Andrade, Resende & Werneck, "Fast local search for
// the maximum independent set problem", J. Heuristics 18 (2012).
#include "codebook_search.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {

bool ConflictTest::operator()(uint64_t a, uint64_t b) const {
  if (timing == CodeTiming::kFreeRunning) return cyclically_closer_than(a, b, length, min_distance);
  return hamming_distance(a, b) < min_distance;
}

uint32_t greedy_independent_set(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n, uint32_t target) {
  uint32_t size = 0;
  for (uint32_t v = 0; v < n && size < target; ++v) {
    bool free = true;
    for (uint32_t i = 0; i < size && free; ++i) free = !conflict(ws.words[v], ws.words[ws.best[i]]);
    if (free) ws.best[size++] = static_cast<uint16_t>(v);
  }
  return size;
}

bool build_conflict_graph(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n) {
  const bool cyclic = conflict.timing == CodeTiming::kFreeRunning;
  const uint32_t shifts = cyclic ? conflict.length : 1;
  uint64_t rotations[64];
  uint32_t entries = 0;
  for (uint32_t v = 0; v < n; ++v) {
    ws.first_neighbour[v] = entries;
    for (uint32_t s = 0; s < shifts; ++s) rotations[s] = rotate_word(ws.words[v], s, conflict.length);
    const uint32_t weight = word_weight(ws.words[v]);
    for (uint32_t u = 0; u < n; ++u) {
      if (u == v) continue;
      // Every shift keeps the weight, so H >= |weight difference|.
      const uint32_t other = word_weight(ws.words[u]);
      if ((weight > other ? weight - other : other - weight) >= conflict.min_distance) continue;
      bool close = false;
      for (uint32_t s = 0; s < shifts && !close; ++s) {
        close = hamming_distance(ws.words[u], rotations[s]) < conflict.min_distance;
      }
      if (!close) continue;
      if (entries == CodebookWorkspace::kMaxNeighbours) return false;
      ws.neighbours[entries++] = static_cast<uint16_t>(u);
    }
  }
  ws.first_neighbour[n] = entries;
  return true;
}

namespace {

// The search state: an independent set S ("solution") of the conflict graph,
// and for every vertex its tightness, the number of its neighbours in S. A
// vertex outside S with tightness 0 is free (can join S). A (1,2)-swap takes x
// out of S and puts in two non-adjacent neighbours of x whose only neighbour
// in S was x. Each iteration forces a random outside vertex into S, restores
// 2-maximality with swaps and keeps the result, or undoes it when it is worse
// (ARW's acceptance rule).
class IndependentSetSearch {
 public:
  IndependentSetSearch(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n, SplitMix64& rng)
      : conflict_(conflict), ws_(ws), n_(n), rng_(rng) {}

  uint32_t run(uint32_t target, uint32_t iterations, uint32_t* used) {
    reset();
    // A greedy maximal set in vertex order (the vertices are already shuffled).
    for (uint32_t v = 0; v < n_; ++v) {
      if (!ws_.in_solution[v] && ws_.tight[v] == 0) insert(static_cast<uint16_t>(v));
    }
    local_search();
    keep_best();
    uint32_t it = 0;
    while (it < iterations && best_size_ < target && size_ < n_) {
      ++it;
      begin_iteration();
      perturb();
      local_search();
      // The forced vertices may leave S now that the others have settled.
      forced_locked_ = false;
      for (uint32_t i = 0; i < forced_count_; ++i) enqueue(forced_[i]);
      local_search();
      if (size_ > best_size_) {
        keep_best();
      } else if (size_ < saved_size_) {
        // Keep a worse set with probability 1 / (1 + delta * delta_best).
        const uint64_t delta = saved_size_ - size_;
        const uint64_t delta_best = best_size_ - size_;
        if (rng_.below(1 + delta * delta_best) != 0) undo_iteration();
      }
    }
    *used = it;
    return best_size_;
  }

 private:
  static constexpr uint16_t kInserted = 0x8000;  // undo-log flag; vertices are < 2^15

  const uint16_t* begin(uint32_t v) const { return ws_.neighbours + ws_.first_neighbour[v]; }
  const uint16_t* end(uint32_t v) const { return ws_.neighbours + ws_.first_neighbour[v + 1]; }

  void reset() {
    for (uint32_t v = 0; v < n_; ++v) {
      ws_.tight[v] = 0;
      ws_.mates[v] = 0;
      ws_.in_solution[v] = 0;
      ws_.queued[v] = 0;
      ws_.listed_free[v] = 0;
    }
    size_ = 0;
    queue_head_ = 0;
    queue_count_ = 0;
    free_count_ = 0;
  }

  // Puts v in S; true when a neighbour now has v as its only solution neighbour.
  bool attach(uint16_t v) {
    ws_.in_solution[v] = 1;
    ws_.position[v] = static_cast<uint16_t>(size_);
    ws_.solution[size_++] = v;
    bool made_one_tight = false;
    for (const uint16_t* z = begin(v); z != end(v); ++z) {
      made_one_tight |= ++ws_.tight[*z] == 1;
      ws_.mates[*z] ^= v;
    }
    return made_one_tight;
  }

  // Takes v out of S; when `notify`, lists neighbours that became free and
  // queues the last solution neighbour of those left with one.
  void detach(uint16_t v, bool notify) {
    ws_.in_solution[v] = 0;
    const uint16_t last = ws_.solution[--size_];
    ws_.solution[ws_.position[v]] = last;
    ws_.position[last] = ws_.position[v];
    for (const uint16_t* z = begin(v); z != end(v); ++z) {
      const uint16_t t = --ws_.tight[*z];
      ws_.mates[*z] ^= v;
      if (notify && t == 0) list_free(*z);
      if (notify && t == 1) enqueue(ws_.mates[*z]);
    }
  }

  void insert(uint16_t v) {
    if (attach(v)) enqueue(v);
    log(static_cast<uint16_t>(v | kInserted));
  }

  void remove(uint16_t v) {
    detach(v, true);
    log(v);
  }

  void log(uint16_t entry) {
    if (log_count_ < CodebookWorkspace::kMaxUndo) {
      ws_.undo_log[log_count_++] = entry;
    } else {
      log_overflow_ = true;
    }
  }

  void enqueue(uint16_t v) {
    if (ws_.queued[v]) return;
    ws_.queued[v] = 1;
    ws_.queue[(queue_head_ + queue_count_) % n_] = v;
    ++queue_count_;
  }

  void list_free(uint16_t v) {
    if (ws_.listed_free[v]) return;
    ws_.listed_free[v] = 1;
    ws_.free_list[free_count_++] = v;
  }

  void fill_free() {
    while (free_count_ > 0) {
      const uint16_t v = ws_.free_list[--free_count_];
      ws_.listed_free[v] = 0;
      if (!ws_.in_solution[v] && ws_.tight[v] == 0) insert(v);
    }
  }

  bool locked(uint16_t v) const {
    for (uint32_t i = 0; forced_locked_ && i < forced_count_; ++i) {
      if (forced_[i] == v) return true;
    }
    return false;
  }

  // (1,2)-swaps until none is left among the queued vertices.
  void local_search() {
    while (queue_count_ > 0) {
      const uint16_t x = ws_.queue[queue_head_];
      queue_head_ = (queue_head_ + 1) % n_;
      --queue_count_;
      ws_.queued[x] = 0;
      if (ws_.in_solution[x] && !locked(x)) try_swap(x);
    }
  }

  void try_swap(uint16_t x) {
    uint32_t k = 0;
    for (const uint16_t* z = begin(x); z != end(x); ++z) {
      if (ws_.tight[*z] == 1) ws_.scratch[k++] = *z;
    }
    for (uint32_t a = 0; a + 1 < k; ++a) {
      for (uint32_t b = a + 1; b < k; ++b) {
        const uint16_t u = ws_.scratch[a];
        const uint16_t w = ws_.scratch[b];
        if (conflict_(ws_.words[u], ws_.words[w])) continue;
        remove(x);
        insert(u);
        insert(w);
        fill_free();
        return;
      }
    }
  }

  // Forces one vertex outside S into it (with probability 1/(2|S| + 2) two or
  // three), removing its neighbours from S; forced vertices stay through the
  // first local search.
  void perturb() {
    uint32_t k = 1;
    if (rng_.below(2 * uint64_t{size_} + 2) == 0) k = 2 + static_cast<uint32_t>(rng_.below(2));
    for (uint32_t i = 0; i < k && size_ < n_; ++i) {
      uint16_t v;
      do {
        v = static_cast<uint16_t>(rng_.below(n_));
      } while (ws_.in_solution[v]);
      for (const uint16_t* z = begin(v); z != end(v); ++z) {
        if (ws_.in_solution[*z]) remove(*z);
      }
      insert(v);
      forced_[forced_count_++] = v;
    }
    forced_locked_ = true;
    fill_free();
  }

  void begin_iteration() {
    for (uint32_t i = 0; i < size_; ++i) ws_.saved[i] = ws_.solution[i];
    saved_size_ = size_;
    log_count_ = 0;
    log_overflow_ = false;
    forced_count_ = 0;
  }

  // Back to the set at the start of the iteration: replay the log backwards,
  // or rebuild from the saved copy when the log overflowed.
  void undo_iteration() {
    if (log_overflow_) {
      reset();
      for (uint32_t i = 0; i < saved_size_; ++i) attach(ws_.saved[i]);
      return;
    }
    for (uint32_t i = log_count_; i > 0; --i) {
      const uint16_t entry = ws_.undo_log[i - 1];
      const uint16_t v = static_cast<uint16_t>(entry & ~kInserted);
      if (entry & kInserted) {
        detach(v, false);
      } else {
        attach(v);
      }
    }
    // The queue and free list are empty after a local search; nothing to clear.
  }

  void keep_best() {
    for (uint32_t i = 0; i < size_; ++i) ws_.best[i] = ws_.solution[i];
    best_size_ = size_;
  }

  const ConflictTest& conflict_;
  CodebookWorkspace& ws_;
  uint32_t n_;
  SplitMix64& rng_;
  uint32_t size_ = 0;
  uint32_t best_size_ = 0;
  uint32_t saved_size_ = 0;
  uint32_t queue_head_ = 0;
  uint32_t queue_count_ = 0;
  uint32_t free_count_ = 0;
  uint32_t log_count_ = 0;
  bool log_overflow_ = false;
  uint16_t forced_[3] = {};
  uint32_t forced_count_ = 0;
  bool forced_locked_ = false;
};

}  // namespace

uint32_t search_independent_set(const ConflictTest& conflict, CodebookWorkspace& ws, uint32_t n, SplitMix64& rng,
                                uint32_t target, uint32_t iterations, uint32_t* used) {
  *used = 0;
  if (n == 0) return 0;
  IndependentSetSearch search(conflict, ws, n, rng);
  return search.run(target, iterations, used);
}

}  // namespace tetrapulse::protocol
