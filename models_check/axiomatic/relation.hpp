// relation.hpp — binary relations over the events of one candidate execution, as bit matrices.
//
// Litmus-sized executions have at most kMaxEvents events, so a relation is one 64-bit row per event (bit b of
// row a: a → b) and an event set is one 64-bit mask. The axioms of the memory models (models.hpp) are written
// with the operators of the papers: union |, intersection &, sequence r.then(s) (r;s), inverse, transitive
// closure plus() (r+), reflexive closure maybe() (r?), restriction [S];r;[T], and the checks acyclic,
// irreflexive, empty.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

namespace frontsteal::axiomatic {

inline constexpr int kMaxEvents = 64;
using EventSet = std::uint64_t;

inline constexpr EventSet bit(int e) { return EventSet{1} << e; }

class Relation {
 public:
  explicit Relation(int events = 0) : n_(events) {}

  int size() const { return n_; }
  void add(int a, int b) { row_[a] |= bit(b); }
  bool has(int a, int b) const { return (row_[a] >> b) & 1U; }
  EventSet successors(int a) const { return row_[a]; }

  // [S]: the identity on the events of S.
  static Relation identity(int events, EventSet s) {
    Relation r(events);
    for (int a = 0; a < events; ++a) {
      if (s & bit(a)) r.add(a, a);
    }
    return r;
  }
  // S × T.
  static Relation product(int events, EventSet s, EventSet t) {
    Relation r(events);
    for (int a = 0; a < events; ++a) {
      if (s & bit(a)) r.row_[a] = t;
    }
    return r;
  }

  Relation operator|(const Relation& o) const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] | o.row_[a];
    return r;
  }
  Relation operator&(const Relation& o) const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] & o.row_[a];
    return r;
  }
  // r \ o
  Relation minus(const Relation& o) const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) r.row_[a] = row_[a] & ~o.row_[a];
    return r;
  }
  // r ; o — a → c when a → b in r and b → c in o for some b.
  Relation then(const Relation& o) const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) {
      for (EventSet m = row_[a]; m != 0; m &= m - 1) r.row_[a] |= o.row_[std::countr_zero(m)];
    }
    return r;
  }
  Relation inverse() const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) {
      for (EventSet m = row_[a]; m != 0; m &= m - 1) r.add(std::countr_zero(m), a);
    }
    return r;
  }
  // [S] ; r ; [T]
  Relation restrict(EventSet s, EventSet t) const {
    Relation r(n_);
    for (int a = 0; a < n_; ++a) {
      if (s & bit(a)) r.row_[a] = row_[a] & t;
    }
    return r;
  }
  // r+ (Warshall's algorithm on rows).
  Relation plus() const {
    Relation r = *this;
    for (int k = 0; k < n_; ++k) {
      for (int a = 0; a < n_; ++a) {
        if (r.has(a, k)) r.row_[a] |= r.row_[k];
      }
    }
    return r;
  }
  // r* = r+ ∪ id,  r? = r ∪ id
  Relation star() const { return plus() | identity(n_, all()); }
  Relation maybe() const { return *this | identity(n_, all()); }

  bool irreflexive() const {
    for (int a = 0; a < n_; ++a) {
      if (has(a, a)) return false;
    }
    return true;
  }
  bool acyclic() const { return plus().irreflexive(); }
  bool empty() const {
    for (int a = 0; a < n_; ++a) {
      if (row_[a] != 0) return false;
    }
    return true;
  }
  EventSet domain() const {
    EventSet s = 0;
    for (int a = 0; a < n_; ++a) {
      if (row_[a] != 0) s |= bit(a);
    }
    return s;
  }
  EventSet range() const {
    EventSet s = 0;
    for (int a = 0; a < n_; ++a) s |= row_[a];
    return s;
  }

 private:
  EventSet all() const { return n_ == kMaxEvents ? ~EventSet{0} : bit(n_) - 1; }

  int n_;
  std::array<EventSet, kMaxEvents> row_{};
};

}  // namespace frontsteal::axiomatic
