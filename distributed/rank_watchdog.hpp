// rank_watchdog.hpp — a per-rank thread that ends the process (exit 86) when the rank has made no progress
// for a time limit, naming the frame and phase it was stuck in: a dead peer or a transport without progress
// then ends the run with a report instead of a hang (mpirun does not always end the others).
//
// The rank marks progress (note_progress) after every item, every frame boundary and every calibrated
// operation; set_phase names what it is doing. The thread only reads these atomics: it never calls MPI.
#pragma once

namespace frontsteal::mpi {

void note_progress() noexcept;
void set_phase(const char* phase) noexcept;  // a string literal (kept by pointer)
void set_frame(int frame) noexcept;
// Starts the thread (no-op for limit_s <= 0); it does nothing until arm_watchdog().
void start_watchdog(double limit_s, int rank);
void arm_watchdog() noexcept;

}  // namespace frontsteal::mpi
