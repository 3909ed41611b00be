// lifelines.cpp — the lifeline graph of lifelines.hpp over the window's lifeline words.
#include "distributed/lifelines.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

namespace frontsteal::mpi {

Lifelines::Lifelines(RmaWindow& win, int rank, int ranks, bool drops_notice)
    : win_(win), rank_(rank), ranks_(ranks), drops_notice_(drops_notice) {
  for (int step = 1; step < ranks; step *= 2) lifelines_.push_back((rank + step) % ranks);
  if (lifelines_.size() > kMaxLifelines) {
    throw std::invalid_argument("lifelines: " + std::to_string(ranks) + " ranks need more than " +
                                std::to_string(kMaxLifelines) + " lifeline words");
  }
  served_.assign(lifelines_.size(), 0);
}

void Lifelines::reset_for_next_frame() {
  win_.accumulate_replace(rank_, kLifelineNotice, std::uint64_t{0});
  win_.accumulate_replace(rank_, kLifelineInvite, std::uint64_t{0});
  for (std::uint32_t k = 0; k < lifelines_.size(); ++k)
    win_.accumulate_replace(rank_, lifeline_hungry(k), std::uint64_t{0});
  std::fill(served_.begin(), served_.end(), 0);
  registration_ = last_invitation_ = 0;
  told_ = false;
}

void Lifelines::register_hungry() {
  ++registration_;
  for (std::uint32_t k = 0; k < lifelines_.size(); ++k) {
    win_.accumulate_replace(lifelines_[k], lifeline_hungry(k), registration_);
  }
}

std::optional<int> Lifelines::new_invitation() {
  const std::uint64_t v = win_.local(kLifelineInvite).load(std::memory_order_acquire);
  if (v == 0 || v == last_invitation_) return std::nullopt;
  last_invitation_ = v;
  return static_cast<int>(v >> 32) - 1;
}

bool Lifelines::notice_seen() { return win_.local(kLifelineNotice).load(std::memory_order_acquire) != 0; }

void Lifelines::tell_frame_over(bool from_count) {
  if (told_ || drops_notice_) return;
  told_ = true;
  if (from_count && rank_ != 0) win_.accumulate_replace(0, kLifelineNotice, std::uint64_t{1});
  const auto i = static_cast<std::uint64_t>(rank_);
  std::uint64_t step = 1;
  while (step <= i) step *= 2;
  for (; i + step < static_cast<std::uint64_t>(ranks_); step *= 2) {
    win_.accumulate_replace(static_cast<int>(i + step), kLifelineNotice, std::uint64_t{1});
  }
}

void Lifelines::invite_hungry(const std::function<bool()>& has_spare) {
  for (std::uint32_t k = 0; k < lifelines_.size(); ++k) {
    const std::uint64_t registered = win_.local(lifeline_hungry(k)).load(std::memory_order_acquire);
    if (registered == served_[k]) continue;
    if (!has_spare()) return;
    served_[k] = registered;
    const int hungry =
        static_cast<int>((rank_ + ranks_ - static_cast<int>((1u << k) % static_cast<unsigned>(ranks_))) % ranks_);
    win_.accumulate_replace(hungry, kLifelineInvite, (static_cast<std::uint64_t>(rank_ + 1) << 32) | registered);
  }
}

}  // namespace frontsteal::mpi
