// request_frame.cpp — FrameRunner's request-based stealing (paper §7; frame_runner.hpp): the idle rank sends
// a request, the busy owner polls MPI_Iprobe between items and answers with the second half of its list.
#include <algorithm>
#include <thread>

#include "distributed/frame_runner.hpp"
#include "distributed/idle_backoff.hpp"

namespace frontsteal::mpi {

void FrameRunner::request_frame(Frame& fr, RangeList list, RangeList& log) {
  log.clear();
  drain_request(fr, list, log);
  protocol_->leave();  // A2
  const auto idle_start = Clock::now();
  const double busy_before = stats_.busy_s;
  int outstanding = -1;
  std::uint32_t empty_replies = 0;
  std::size_t next_victim = 0;
  Clock::time_point sent_at{};
  while (true) {
    serve_requests(nullptr);
    if (outstanding < 0) {
      if (protocol_->all_idle()) break;  // A3
      if (victims_.empty()) continue;
      outstanding = victims_[next_victim++ % victims_.size()];
      const std::int32_t frame = fr.f;
      check_mpi(MPI_Send(&frame, 1, MPI_INT32_T, outstanding, kTagRequest, MPI_COMM_WORLD), "MPI_Send");
      stats_.bytes += 4;
      stats_.steal_attempts += 1;
      sent_at = Clock::now();
      continue;
    }
    int flag = 0;
    MPI_Status st;
    check_mpi(MPI_Iprobe(outstanding, kTagReply, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
    if (!flag) continue;
    int words = 0;
    MPI_Get_count(&st, MPI_UINT32_T, &words);
    std::vector<std::uint32_t> buf(static_cast<std::size_t>(words));
    check_mpi(MPI_Recv(buf.data(), words, MPI_UINT32_T, outstanding, kTagReply, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
    outstanding = -1;
    if (words == 0) {  // an empty answer: back off a little before asking the next victim (as rma's idle loop)
      idle_back_off(++empty_replies, /*yield_first=*/false);
      continue;
    }
    empty_replies = 0;
    record_steal(Clock::now() - sent_at);
    RangeList share;
    for (int i = 0; i + 1 < words; i += 2) share.push_back({buf[i], buf[i + 1]});
    drain_request(fr, std::move(share), log);
    protocol_->leave();  // A2 (the victim joined for us, A1, before it replied)
  }
  stats_.idle_s += std::chrono::duration<double>(Clock::now() - idle_start).count() - (stats_.busy_s - busy_before);
  // Frame end: every rank arrives with no outstanding request; answer stragglers until all have arrived.
  MPI_Request barrier;
  check_mpi(MPI_Ibarrier(MPI_COMM_WORLD, &barrier), "MPI_Ibarrier");
  for (int done = 0; !done;) {
    serve_requests(nullptr);
    check_mpi(MPI_Test(&barrier, &done, MPI_STATUS_IGNORE), "MPI_Test");
  }
}

// The request owner: its list is private; between items it polls for steal requests.
void FrameRunner::drain_request(Frame& fr, RangeList list, RangeList& log) {
  std::size_t i = 0;
  while (true) {
    const auto t0 = Clock::now();
    if (request_poll_.due(t0)) serve_requests(&list, &i);
    record_owner_op(Clock::now() - t0);  // per item: the poll and any replies when due, else the gate's check
    while (i < list.size() && list[i].empty()) ++i;
    if (i >= list.size()) return;
    const ItemId id = list[i].begin++;
    append_merging(log, {id, id + 1});
    execute(fr, id);
  }
}

namespace {

// Splits list[index..] as §7's owner does: keeps the first half (items_left_to_victim), returns the second as
// [begin, end) word pairs. With keep_share (the negative control) the owner also keeps what it sends.
std::vector<std::uint32_t> split_off_share(RangeList& list, std::size_t index, bool keep_share) {
  std::vector<std::uint32_t> reply;
  std::uint64_t remaining = 0;
  for (std::size_t k = index; k < list.size(); ++k) remaining += list[k].size();
  if (remaining < 2) return reply;
  std::uint64_t keep = items_left_to_victim(remaining);
  RangeList mine(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(index));
  for (std::size_t k = index; k < list.size(); ++k) {
    const IdRange r = list[k];
    if (keep >= r.size()) {
      keep -= r.size();
      mine.push_back(r);
      continue;
    }
    const IdRange kept{r.begin, static_cast<ItemId>(r.begin + keep)};
    const IdRange sent{kept.end, r.end};
    keep = 0;
    if (!kept.empty()) mine.push_back(kept);
    if (!sent.empty()) reply.insert(reply.end(), {sent.begin, sent.end});
  }
  if (!keep_share) list = std::move(mine);
  return reply;
}

}  // namespace

// Answers every pending steal request: with the second half of list[i..] when this rank is busy (list
// given), with an empty reply otherwise. The poll's cost is what §7 says busy processors must pay.
void FrameRunner::serve_requests(RangeList* list, std::size_t* index) {
  while (true) {
    int flag = 0;
    MPI_Status st;
    check_mpi(MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
    if (!flag) return;
    std::int32_t frame = 0;
    check_mpi(MPI_Recv(&frame, 1, MPI_INT32_T, st.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
    const std::vector<std::uint32_t> reply = list != nullptr
                                                 ? split_off_share(*list, *index, o_.defect == "request-keeps-share")
                                                 : std::vector<std::uint32_t>{};
    if (!reply.empty()) protocol_->join();  // A1 on the thief's behalf, before the share leaves (I-T)
    check_mpi(
        MPI_Send(reply.data(), static_cast<int>(reply.size()), MPI_UINT32_T, st.MPI_SOURCE, kTagReply, MPI_COMM_WORLD),
        "MPI_Send");
    stats_.bytes += 4.0 * static_cast<double>(reply.size());
    stats_.requests_served += 1;
  }
}

}  // namespace frontsteal::mpi
