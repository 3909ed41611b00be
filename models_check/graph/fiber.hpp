// fiber.hpp — the program's threads as fibers on one OS thread, so the explorer decides exactly when each runs and
// nothing runs concurrently with it.
//
// A fiber runs its body until the body returns or the fiber suspends itself; the explorer resumes it. A fiber
// that blocks forever (a wait the explorer will not satisfy in this run) is simply never resumed: its stack is
// reused by the next run, and whatever its frames hold is dropped without destructors (the protocol's frames hold
// ids and counters; the frame loop's heap blocks belong to objects the program owns and destroys).
//
// WHY NOT ONLY ucontext. The replay switches fibers at every recorded event (explorer.cpp: turn-taking), hundreds of
// times per run, and glibc's swapcontext saves and restores the signal mask with a system call at each switch: on
// these VMs that was half of the explorer's time. On x86-64 (outside the sanitizer builds, whose runtimes must be
// told of stack switches) a switch is the System V ABI's callee-saved registers and the stack pointer, nothing
// more: no code here changes the signal mask, the x87 control word or MXCSR, so those need no saving. Elsewhere
// the POSIX ucontext path runs.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>

#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define FRONTSTEAL_FIBER_REGISTER_SWITCH 1
#else
#include <ucontext.h>
#endif

namespace frontsteal::graph {

#if FRONTSTEAL_FIBER_REGISTER_SWITCH
namespace fiber_detail {
// Pushes the callee-saved registers on the current stack, stores the stack pointer in *save, loads `load` and pops
// the registers saved there: a call that returns on the other stack.
extern "C" void frontsteal_fiber_switch(void** save, void* load);
}  // namespace fiber_detail
#endif

class Fiber {
 public:
  static constexpr std::size_t kStackBytes = 256 * 1024;

  Fiber() : stack_(std::make_unique<char[]>(kStackBytes)) {}
  Fiber(const Fiber&) = delete;
  Fiber& operator=(const Fiber&) = delete;

  // Prepares the fiber to run `body` from its start when next resumed.
  void start(std::function<void()> body) {
    body_ = std::move(body);
    finished_ = false;
#if FRONTSTEAL_FIBER_REGISTER_SWITCH
    // The first switch pops six registers and returns into the trampoline (fiber.cpp), which finds `this` in r12
    // and calls entry(). Nine words: r15, r14, r13, r12, rbx, rbp, the return address, two pad words, so that the
    // trampoline starts with the stack 16-byte aligned, as its call needs.
    auto top = reinterpret_cast<std::uintptr_t>(stack_.get() + kStackBytes) & ~std::uintptr_t{15};
    auto* frame = reinterpret_cast<void**>(top) - 9;
    for (int i = 0; i < 9; ++i) frame[i] = nullptr;
    frame[3] = this;
    frame[6] = trampoline_address();
    sp_ = frame;
#else
    if (getcontext(&context_) != 0) throw std::runtime_error("getcontext failed");
    context_.uc_stack.ss_sp = stack_.get();
    context_.uc_stack.ss_size = kStackBytes;
    context_.uc_link = &home_;
    const auto self = reinterpret_cast<std::uintptr_t>(this);
    makecontext(&context_, reinterpret_cast<void (*)()>(&Fiber::entry_parts), 2, static_cast<unsigned>(self >> 32),
                static_cast<unsigned>(self & 0xffffffffu));
#endif
  }
  // Runs the fiber until it returns or suspends.
  void resume() {
#if FRONTSTEAL_FIBER_REGISTER_SWITCH
    fiber_detail::frontsteal_fiber_switch(&home_sp_, sp_);
#else
    if (swapcontext(&home_, &context_) != 0) throw std::runtime_error("swapcontext failed");
#endif
  }
  // Called on the fiber: back to the explorer.
  void suspend() {
#if FRONTSTEAL_FIBER_REGISTER_SWITCH
    fiber_detail::frontsteal_fiber_switch(&sp_, home_sp_);
#else
    if (swapcontext(&context_, &home_) != 0) throw std::runtime_error("swapcontext failed");
#endif
  }
  bool finished() const { return finished_; }

  // Where the fiber's body starts (the trampoline calls it with the fiber); it returns to the explorer for good.
  static void entry(Fiber* self) {
    self->body_();
    self->finished_ = true;
#if FRONTSTEAL_FIBER_REGISTER_SWITCH
    self->suspend();  // never resumed: start() prepares a fresh frame
    std::terminate();
#endif
  }

 private:
#if FRONTSTEAL_FIBER_REGISTER_SWITCH
  static void* trampoline_address();
  void* sp_ = nullptr;
  void* home_sp_ = nullptr;
#else
  static void entry_parts(unsigned hi, unsigned lo) {
    entry(reinterpret_cast<Fiber*>((static_cast<std::uintptr_t>(hi) << 32) | lo));
  }
  ucontext_t context_{};
  ucontext_t home_{};
#endif
  std::unique_ptr<char[]> stack_;
  std::function<void()> body_;
  bool finished_ = false;
};

}  // namespace frontsteal::graph
