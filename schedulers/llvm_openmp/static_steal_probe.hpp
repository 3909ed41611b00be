// static_steal_probe.hpp — the proof that a schedule(runtime) loop runs under libomp's static_steal, and the
// static ranges it deals: thread t owns the contiguous chunk range starting at t * (K / P) + min(t, K % P) of
// the K chunks, takes from its front, and a thief takes from a victim's back (kmp_dispatch.cpp).
//
// omp_get_schedule cannot report static_steal (libomp 14 maps it to "dynamic"), so the child proves it with a
// probe before it says ready, a loop of 64 P iterations in which
//   (a) each thread, at its first iteration, waits until every thread has taken its first one: under static
//       ranges (static or static_steal) thread t's first iteration is the start of its own range, since no
//       one can steal from a thread that is blocked in its first item; under a shared counter
//       (--schedule monotonic-dynamic) thread 1's first is 1;
//   (b) then thread 0 stays in its first iteration until some iteration has run on a thread other than its
//       static owner: under static_steal the others finish their ranges and steal from thread 0; under plain
//       static (--schedule static) nothing ever does, and the probe fails after 10 s.
// Both are deterministic (a forced interleaving, no timing luck); only a thread that does not arrive at all
// within 10 s in (a) makes the probe repeat (up to 5 times). With P = 1 there is nothing to prove (and libomp
// uses no ranges).
#pragma once

namespace frontsteal::llvm_openmp {

// The first chunk of thread t's static range in libomp's static_steal.
long long range_start(long long t, long long chunks, long long threads);
// The static owner of chunk c (the inverse of range_start).
int owner_of(long long c, long long chunks, long long threads);

// The probe above. Returns the attempts it took, or 0 when static_steal was not observed.
int probe_static_steal(int threads);

}  // namespace frontsteal::llvm_openmp
