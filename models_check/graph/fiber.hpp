// fiber.hpp — the program's threads as fibers on one OS thread (POSIX ucontext), so the explorer decides
// exactly when each runs and nothing runs concurrently with it.
//
// A fiber runs its body until the body returns or the fiber suspends itself; the explorer resumes it. A fiber
// that blocks forever (a wait the explorer will not satisfy in this run) is simply never resumed: its stack is
// reused by the next run, and whatever its frames hold is dropped without destructors (the protocol's frames hold
// ids and counters; the frame loop's heap blocks belong to objects the program owns and destroys).
#pragma once

#include <ucontext.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>

namespace frontsteal::graph {

class Fiber {
 public:
  static constexpr std::size_t kStackBytes = 256 * 1024;

  Fiber() : stack_(std::make_unique<char[]>(kStackBytes)) {}
  Fiber(const Fiber&) = delete;
  Fiber& operator=(const Fiber&) = delete;

  // Prepares the fiber to run `body` from its start when next resumed; `home` is where it returns.
  void start(std::function<void()> body, ucontext_t* home) {
    body_ = std::move(body);
    finished_ = false;
    if (getcontext(&context_) != 0) throw std::runtime_error("getcontext failed");
    context_.uc_stack.ss_sp = stack_.get();
    context_.uc_stack.ss_size = kStackBytes;
    context_.uc_link = home;
    home_ = home;
    const auto self = reinterpret_cast<std::uintptr_t>(this);
    makecontext(&context_, reinterpret_cast<void (*)()>(&Fiber::entry), 2, static_cast<unsigned>(self >> 32),
                static_cast<unsigned>(self & 0xffffffffu));
  }
  // Runs the fiber until it returns or suspends.
  void resume() {
    if (swapcontext(home_, &context_) != 0) throw std::runtime_error("swapcontext failed");
  }
  // Called on the fiber: back to the explorer.
  void suspend() {
    if (swapcontext(&context_, home_) != 0) throw std::runtime_error("swapcontext failed");
  }
  bool finished() const { return finished_; }

 private:
  static void entry(unsigned hi, unsigned lo) {
    auto* self = reinterpret_cast<Fiber*>((static_cast<std::uintptr_t>(hi) << 32) | lo);
    self->body_();
    self->finished_ = true;
  }

  std::unique_ptr<char[]> stack_;
  ucontext_t context_{};
  ucontext_t* home_ = nullptr;
  std::function<void()> body_;
  bool finished_ = false;
};

}  // namespace frontsteal::graph
