// state_home.hpp — where the protocol's shared words live, so that one protocol source (stealing_protocol.hpp,
// try_lock.hpp, active_workers.hpp) runs over backends whose memory is not this process's objects.
//
// Most backends (std, the chaos backend, Relacy, the execution-graph backend) keep every word as an object of
// this process: the state types construct their words in place, with their initial values. That is LocalHome,
// the default, and the state types then compile to exactly what they were written as (a member
// std::atomic<std::uint32_t> front{0u}).
//
// A backend whose words live elsewhere declares `using Home = ...;` (for an MPI-3 window: the window and the
// rank whose part holds the words). The state types then build each word as a handle, from the home and the
// word's name (StateWord), and each element of the list body from the home and its index; the protocol code is
// unchanged: it names words (slot.front, slot.entries[i]), and the backend turns each labelled access into an
// instruction on local memory or a one-sided operation on another rank's.
//
// CONTRACT for a backend with a Home
//   Atomic<T>(const Home&, StateWord)                   a handle to that word (a cheap value)
//   Cell<T>(const Home&, StateWord, std::uint32_t i)    a handle to element i of an array word, or (i = 0) to a
//                                                       scalar cell
//   Initial values: a remote home's words start as its owner made them (an MPI window is zeroed at creation);
//   the initial values the state types pass are for LocalHome only. Every word the protocol starts from a
//   non-zero value is re-armed explicitly before use (ActiveWorkers::rearm), so both agree.
#pragma once

#include <cstdint>
#include <memory>
#include <type_traits>

namespace frontsteal {

// The protocol's shared words, by name: what a remote home maps to an address.
enum class StateWord : std::uint8_t {
  kFront,        // ActivitySlot::front      Front[p]
  kTransient,    // ActivitySlot::transient  ListTransient[p]
  kEnd,          // ActivitySlot::end        End of ActivityList[p]
  kLock,         // TryLock's word           LockList[p]
  kEntryCount,   // ActivitySlot::entry_count
  kEntries,      // ActivitySlot::entries    the list body (an array)
  kActiveCount,  // ActiveWorkers' count
};

// Words are objects of this process, constructed in place.
struct LocalHome {};

namespace detail {
template <class Backend>
struct HomeOf {
  using type = LocalHome;
};
template <class Backend>
requires requires { typename Backend::Home; }
struct HomeOf<Backend> {
  using type = typename Backend::Home;
};
}  // namespace detail

template <class Backend>
using HomeOf = typename detail::HomeOf<Backend>::type;

template <class Backend>
inline constexpr bool kLocalHome = std::is_same_v<HomeOf<Backend>, LocalHome>;

// An atomic word of the protocol state: in place with `initial` (LocalHome), or a handle into the home.
// Returned as a prvalue, so non-movable atomics (std::atomic, rl::atomic) are built directly in the member.
template <class Backend, class T>
typename Backend::template Atomic<T> atomic_word([[maybe_unused]] const HomeOf<Backend>& home,
                                                 [[maybe_unused]] StateWord word, T initial) {
  if constexpr (kLocalHome<Backend>) {
    return typename Backend::template Atomic<T>(initial);
  } else {
    return typename Backend::template Atomic<T>(home, word);
  }
}

// A plain (non-atomic) scalar cell of the protocol state.
template <class Backend, class T>
typename Backend::template Cell<T> cell_word([[maybe_unused]] const HomeOf<Backend>& home,
                                             [[maybe_unused]] StateWord word) {
  if constexpr (kLocalHome<Backend>) {
    return typename Backend::template Cell<T>{};
  } else {
    return typename Backend::template Cell<T>(home, word, 0);
  }
}

// An array of plain cells (the list body): owned cells for LocalHome, handles computed per index otherwise.
// operator[] returns a reference to the cell, or a handle by value; labelled_access.hpp's read and write take
// either.
template <class Backend, class T>
class CellArray {
 public:
  using Cell = typename Backend::template Cell<T>;

  CellArray([[maybe_unused]] const HomeOf<Backend>& home, [[maybe_unused]] StateWord word, std::uint32_t size) {
    if constexpr (kLocalHome<Backend>) {
      storage_ = std::make_unique<Cell[]>(size);
    } else {
      storage_ = Remote{home, word};
    }
  }
  CellArray(const CellArray&) = delete;
  CellArray& operator=(const CellArray&) = delete;

  decltype(auto) operator[](std::uint32_t i) noexcept {
    if constexpr (kLocalHome<Backend>) {
      return (storage_[i]);
    } else {
      return Cell(storage_.home, storage_.word, i);
    }
  }
  decltype(auto) operator[](std::uint32_t i) const noexcept {
    if constexpr (kLocalHome<Backend>) {
      return static_cast<const Cell&>(storage_[i]);
    } else {
      return Cell(storage_.home, storage_.word, i);
    }
  }

 private:
  struct Remote {
    HomeOf<Backend> home{};
    StateWord word{};
  };
  // LocalHome: the cells themselves (one pointer, as a plain array member would be); otherwise where they are.
  std::conditional_t<kLocalHome<Backend>, std::unique_ptr<Cell[]>, Remote> storage_;
};

}  // namespace frontsteal
