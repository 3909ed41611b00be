// fiber.cpp — the x86-64 register switch and the trampoline a fresh fiber starts in (fiber.hpp says why).
#include "models_check/graph/fiber.hpp"

#if FRONTSTEAL_FIBER_REGISTER_SWITCH

extern "C" void frontsteal_fiber_trampoline();
extern "C" void frontsteal_fiber_entry(void* self) {
  frontsteal::graph::Fiber::entry(static_cast<frontsteal::graph::Fiber*>(self));
}

// System V x86-64: rbx, rbp and r12–r15 are callee-saved; the caller of frontsteal_fiber_switch has saved the
// rest, so these and the stack pointer are the whole state a switch must carry.
asm(R"(
    .text
    .globl frontsteal_fiber_switch
    .type frontsteal_fiber_switch, @function
frontsteal_fiber_switch:
    pushq %rbp
    pushq %rbx
    pushq %r12
    pushq %r13
    pushq %r14
    pushq %r15
    movq %rsp, (%rdi)
    movq %rsi, %rsp
    popq %r15
    popq %r14
    popq %r13
    popq %r12
    popq %rbx
    popq %rbp
    ret
    .size frontsteal_fiber_switch, .-frontsteal_fiber_switch

    .globl frontsteal_fiber_trampoline
    .type frontsteal_fiber_trampoline, @function
frontsteal_fiber_trampoline:
    movq %r12, %rdi
    call frontsteal_fiber_entry
    ud2
    .size frontsteal_fiber_trampoline, .-frontsteal_fiber_trampoline
)");

void* frontsteal::graph::Fiber::trampoline_address() { return reinterpret_cast<void*>(&frontsteal_fiber_trampoline); }

#endif
