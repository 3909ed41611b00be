// relation.hpp — binary relations over the events of one execution, as bit matrices.
//
// A relation is one bit row per event (bit b of row a: a → b) and an event set is one bit mask. Litmus-sized
// executions have at most kMaxEvents events, so their sets are one 64-bit word (EventSet, Relation); the
// execution graphs of whole protocol runs (models_check/graph/) have hundreds of events and use WideSet, a
// fixed array of words, with the same operators. The memory models' axioms (models.hpp) are written once,
// over either, with the operators of the papers: union |, intersection &, sequence r.then(s) (r;s), inverse,
// transitive closure plus() (r+), reflexive closure maybe() (r?), restriction [S];r;[T], and the checks
// acyclic, irreflexive, empty.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace frontsteal::axiomatic {

inline constexpr int kMaxEvents = 64;
using EventSet = std::uint64_t;

inline constexpr EventSet bit(int e) { return EventSet{1} << e; }

// A set of up to kWideEvents events.
inline constexpr int kWideWords = 8;
inline constexpr int kWideEvents = 64 * kWideWords;
struct WideSet {
  std::array<std::uint64_t, kWideWords> word{};

  WideSet operator|(const WideSet& o) const {
    WideSet r;
    for (int i = 0; i < kWideWords; ++i) r.word[i] = word[i] | o.word[i];
    return r;
  }
  WideSet operator&(const WideSet& o) const {
    WideSet r;
    for (int i = 0; i < kWideWords; ++i) r.word[i] = word[i] & o.word[i];
    return r;
  }
  WideSet operator~() const {
    WideSet r;
    for (int i = 0; i < kWideWords; ++i) r.word[i] = ~word[i];
    return r;
  }
  WideSet& operator|=(const WideSet& o) {
    for (int i = 0; i < kWideWords; ++i) word[i] |= o.word[i];
    return *this;
  }
  friend bool operator==(const WideSet&, const WideSet&) = default;
};

// The operations the relation needs on either kind of set.
inline bool has_bit(EventSet s, int e) { return (s >> e) & 1U; }
inline bool has_bit(const WideSet& s, int e) { return (s.word[e >> 6] >> (e & 63)) & 1U; }
inline bool none(EventSet s) { return s == 0; }
inline bool none(const WideSet& s) { return s == WideSet{}; }
template <class Set>
inline Set single(int e) {
  if constexpr (std::is_same_v<Set, EventSet>) {
    return bit(e);
  } else {
    Set s;
    s.word[e >> 6] = std::uint64_t{1} << (e & 63);
    return s;
  }
}
template <class Set>
inline void insert(Set& s, int e) {
  s |= single<Set>(e);
}
inline void insert(WideSet& s, int e) { s.word[e >> 6] |= std::uint64_t{1} << (e & 63); }
// The first `n` events.
template <class Set>
inline Set first(int n) {
  if constexpr (std::is_same_v<Set, EventSet>) {
    return n == kMaxEvents ? ~EventSet{0} : bit(n) - 1;
  } else {
    Set s;
    for (int i = 0; i < kWideWords; ++i) {
      const int lo = 64 * i;
      s.word[i] = n >= lo + 64 ? ~std::uint64_t{0} : n <= lo ? 0 : (std::uint64_t{1} << (n - lo)) - 1;
    }
    return s;
  }
}
template <class F>
inline void for_each(EventSet s, F&& f) {
  for (EventSet m = s; m != 0; m &= m - 1) f(std::countr_zero(m));
}
template <class F>
inline void for_each(const WideSet& s, F&& f) {
  for (int i = 0; i < kWideWords; ++i) {
    for (std::uint64_t m = s.word[i]; m != 0; m &= m - 1) f(64 * i + std::countr_zero(m));
  }
}
template <class Set>
inline constexpr int capacity() {
  return std::is_same_v<Set, EventSet> ? kMaxEvents : kWideEvents;
}

template <class Set>
class BasicRelation {
 public:
  explicit BasicRelation(int events = 0) : n_(events), row_(static_cast<std::size_t>(events)) {}

  int size() const { return n_; }
  void add(int a, int b) {
    insert(row_[a], b);
    diagonal_ = false;
  }
  // a × S.
  void add_all(int a, const Set& s) {
    row_[a] |= s;
    diagonal_ = false;
  }
  bool has(int a, int b) const { return has_bit(row_[a], b); }
  const Set& successors(int a) const { return row_[a]; }

  // [S]: the identity on the events of S. It remembers S, so that sequencing with it is a restriction
  // (then() below), not a product.
  static BasicRelation identity(int events, const Set& s) {
    BasicRelation r(events);
    const Set diagonal = s & first<Set>(events);
    for_each(diagonal, [&](int a) { r.add(a, a); });
    r.diagonal_ = true;
    r.diagonal_set_ = diagonal;
    return r;
  }
  // S × T.
  static BasicRelation product(int events, const Set& s, const Set& t) {
    BasicRelation r(events);
    for_each(s & first<Set>(events), [&](int a) { r.row_[a] = t; });
    return r;
  }

  BasicRelation operator|(const BasicRelation& o) const {
    BasicRelation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] | o.row_[a];
    return r;
  }
  BasicRelation operator&(const BasicRelation& o) const {
    BasicRelation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] & o.row_[a];
    return r;
  }
  // r \ o
  BasicRelation minus(const BasicRelation& o) const {
    BasicRelation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] & ~o.row_[a];
    return r;
  }
  // r ; o — a → c when a → b in r and b → c in o for some b.
  BasicRelation then(const BasicRelation& o) const {
    BasicRelation r(n_);
    if (o.diagonal_) {  // r;[S]: keep the edges into S
      for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] & o.diagonal_set_;
      return r;
    }
    if (diagonal_) {  // [S];o: keep the rows of S
      for_each(diagonal_set_, [&](int a) { r.row_[a] = o.row_[a]; });
      return r;
    }
    for (int a = 0; a < n_; ++a) for_each(row_[a], [&](int b) { r.row_[a] |= o.row_[b]; });
    return r;
  }
  BasicRelation inverse() const {
    BasicRelation r(n_);
    for (int a = 0; a < n_; ++a) for_each(row_[a], [&](int b) { r.add(b, a); });
    return r;
  }
  // [S] ; r ; [T]
  BasicRelation restrict(const Set& s, const Set& t) const {
    BasicRelation r(n_);
    for (int a = 0; a < n_; ++a) {
      if (has_bit(s, a)) r.row_[a] = row_[a] & t;
    }
    return r;
  }
  // r+ (Warshall's algorithm on rows).
  BasicRelation plus() const {
    BasicRelation r = *this;
    r.diagonal_ = false;
    for (int k = 0; k < n_; ++k) {
      for (int a = 0; a < n_; ++a) {
        if (r.has(a, k)) r.row_[a] |= r.row_[k];
      }
    }
    return r;
  }
  // r* = r+ ∪ id,  r? = r ∪ id
  BasicRelation star() const { return plus() | identity(n_, all()); }
  BasicRelation maybe() const { return *this | identity(n_, all()); }

  bool irreflexive() const {
    for (int a = 0; a < n_; ++a) {
      if (has(a, a)) return false;
    }
    return true;
  }
  // Acyclic: a depth-first search for a back edge (linear in the edges; plus() would be cubic).
  bool acyclic() const {
    std::vector<std::uint8_t> state(static_cast<std::size_t>(n_), 0);  // 0 new, 1 on the stack, 2 done
    std::vector<std::pair<int, int>> stack;                            // (event, next successor to try)
    for (int root = 0; root < n_; ++root) {
      if (state[root] != 0) continue;
      stack.push_back({root, 0});
      state[root] = 1;
      while (!stack.empty()) {
        auto& [a, from] = stack.back();
        int next = -1;
        for (int b = from; b < n_; ++b) {
          if (has(a, b)) {
            next = b;
            break;
          }
        }
        if (next < 0) {
          state[a] = 2;
          stack.pop_back();
          continue;
        }
        from = next + 1;
        if (state[next] == 1) return false;
        if (state[next] == 0) {
          state[next] = 1;
          stack.push_back({next, 0});
        }
      }
    }
    return true;
  }
  bool empty() const {
    for (int a = 0; a < n_; ++a) {
      if (!none(row_[a])) return false;
    }
    return true;
  }
  Set domain() const {
    Set s{};
    for (int a = 0; a < n_; ++a) {
      if (!none(row_[a])) insert(s, a);
    }
    return s;
  }
  Set range() const {
    Set s{};
    for (int a = 0; a < n_; ++a) s |= row_[a];
    return s;
  }

 private:
  Set all() const { return first<Set>(n_); }

  int n_;
  std::vector<Set> row_;
  bool diagonal_ = false;  // made by identity() and not changed since (every other operation builds a new one)
  Set diagonal_set_{};
};

using Relation = BasicRelation<EventSet>;
using WideRelation = BasicRelation<WideSet>;

}  // namespace frontsteal::axiomatic
