// calibration_operations.hpp — the names of the operations frontsteal-mpi --calibrate times, as they appear in
// its JSON ("operations"[].operation), and the ones the distributed simulator reads back
// (rma_simulator.hpp's latencies_from_calibration). One list for the writer and the reader, so a renamed
// operation cannot leave the simulator looking for a row that is no longer written.
#pragma once

#include <string_view>

namespace frontsteal::mpi::calibration_ops {

inline constexpr std::string_view kGet = "MPI_Get 4 B + MPI_Win_flush (remote)";
inline constexpr std::string_view kPut = "MPI_Put 4 B + MPI_Win_flush (remote)";
inline constexpr std::string_view kCompareAndSwap = "MPI_Compare_and_swap + flush (remote)";
inline constexpr std::string_view kFetchAndOp = "MPI_Fetch_and_op SUM + flush (remote)";
// 64 fetch-and-ops issued back to back and completed by one flush, the time divided by 64: what one atomic
// occupies the slowest stage (the target's service, where the target's progress engine applies each one).
inline constexpr std::string_view kFetchAndOpPipelined = "MPI_Fetch_and_op SUM x64 + one flush, per operation";
inline constexpr std::string_view kFlush = "MPI_Win_flush alone (nothing pending)";
inline constexpr std::string_view kWinSync = "MPI_Win_sync (owner F1)";
inline constexpr std::string_view kClaimWithSync = "RMA owner claim, F1 = MPI_Win_sync + fence";
inline constexpr std::string_view kClaim = "RMA owner claim, F1 = fence only (default)";
inline constexpr std::string_view kProgressCall = "owner progress call (MPI_Iprobe, unused tag)";
inline constexpr std::string_view kRequestPoll = "request owner poll (MPI_Iprobe, nothing pending)";
inline constexpr std::string_view kPingPong = "MPI_Send/MPI_Recv ping-pong 4 B (round trip)";
inline constexpr std::string_view kClockFloor = "clock pair alone (measurement floor)";
inline constexpr std::string_view kView = "thief's view: one MPI_Get, 16 B + 64 entries";
inline constexpr std::string_view kStealView = "remote steal, core's Thief, one view (default)";
inline constexpr std::string_view kStealWords = "remote steal, core's Thief, word-by-word reads";

}  // namespace frontsteal::mpi::calibration_ops
