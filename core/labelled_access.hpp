// labelled_access.hpp — the only way protocol files touch shared memory: one call per labelled site.
//
// Access<Backend, Policy>::load<Site::kOwnerReadEnd>(slot.end) asks the policy for the site's order, checks
// at compile time that the site is a load, and passes the site and the caller's source location to the
// backend. A protocol file therefore never names a memory order, a fence instruction or a backend type: the
// orders live in policies.hpp, the instructions in the backend.
#pragma once

#include "core/source_location.hpp"

#include "core/memory_order.hpp"
#include "core/site.hpp"

namespace frontsteal {

template <class Backend, class Policy>
struct Access {
  using Where = SourceLocation;

  template <Site S, class A>
  static auto load(const A& a, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kLoad, "site is not a load");
    return Backend::load(a, Policy::order(S), S, where);
  }
  template <Site S, class A, class T>
  static void store(A& a, T v, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kStore, "site is not a store");
    Backend::store(a, v, Policy::order(S), S, where);
  }
  template <Site S, class A, class T>
  static auto exchange(A& a, T v, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kReadModifyWrite, "site is not a read-modify-write");
    return Backend::exchange(a, v, Policy::order(S), S, where);
  }
  template <Site S, class A, class T>
  static auto fetch_add(A& a, T v, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kReadModifyWrite, "site is not a read-modify-write");
    return Backend::fetch_add(a, v, Policy::order(S), S, where);
  }
  template <Site S, class A, class T>
  static auto fetch_sub(A& a, T v, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kReadModifyWrite, "site is not a read-modify-write");
    return Backend::fetch_sub(a, v, Policy::order(S), S, where);
  }
  // Strong compare-exchange: true, and `expected` unchanged, if `a` held `expected` (then it holds `desired`);
  // false with `expected` := the value found. The policy's order applies to the success case. The failure
  // order is always relaxed, derived here rather than asked of the policy: a protocol may use a failed CAS
  // only as "someone else won" (the Chase–Lev owner and thieves then return without touching the element),
  // never to read what the winner published, so the failed load needs no order (Lê et al. PPoPP'13 use
  // relaxed there too). A site whose failure result carries data would need its own failure order.
  template <Site S, class A, class T>
  static bool compare_exchange(A& a, T& expected, T desired, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kReadModifyWrite, "site is not a read-modify-write");
    return Backend::compare_exchange(a, expected, desired, Policy::order(S), Mo::kRelaxed, S, where);
  }
  template <Site S>
  static void fence(Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kFence, "site is not a fence");
    Backend::fence(Policy::fence(S), S, where);
  }
  // Blocking wait for a value change (frame boundaries only).
  template <Site S, class A, class T>
  static void wait_while_equal(const A& a, T old, Where where = Where::current()) noexcept {
    static_assert(info(S).kind == SiteKind::kLoad, "site is not a load");
    Backend::wait_while_equal(a, old, Policy::order(S), S, where);
  }
  // Diagnostics only (watchdog snapshots, stress/watchdog.hpp), never a protocol step: a relaxed atomic read
  // from a thread outside the protocol. Racy by design (the value may be stale the moment it is read) but
  // atomic, so it is no data race; it carries no site, so no policy, checker or chaos backend sees it.
  template <class A>
  static auto peek(const A& a) noexcept {
    return Backend::peek(a);
  }
  // Plain shared cells: no order, but the backend sees them (Relacy checks them for data races).
  template <class C>
  static auto read(const C& c, Where where = Where::current()) noexcept {
    return Backend::read(c, where);
  }
  // `c` is a cell, or a handle to one (state_home.hpp: CellArray::operator[] of a remote home returns one).
  template <class C, class T>
  static void write(C&& c, T v, Where where = Where::current()) noexcept {
    Backend::write(c, v, where);
  }
};

}  // namespace frontsteal
