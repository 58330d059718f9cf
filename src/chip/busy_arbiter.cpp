#include "sercon/chip/busy_arbiter.hpp"

#include <algorithm>
#include <stdexcept>

namespace sercon::chip {

BusyArbiter::BusyArbiter(sim::Scheduler& scheduler, const MclkGrid& mclk, std::uint16_t ram_words,
                         std::function<void(bool)> drive_busyn)
    : scheduler_(scheduler),
      mclk_(mclk),
      drive_busyn_(std::move(drive_busyn)),
      last_used_(ram_words, -1) {}

BusyArbiter::~BusyArbiter() { scheduler_.cancel(release_event_); }

void BusyArbiter::beyond_the_ram() { throw std::out_of_range("BusyArbiter: word beyond the RAM"); }

bool BusyArbiter::host_access(std::uint16_t word) {
  const sim::Time now = scheduler_.now();
  const sim::Time used = last_used_.at(word);
  host_word_ = word;
  host_time_ = now;
  if (used < 0) return false;  // never used
  if (used != now && period_index(used) != period_index(now)) return false;
  pull_low(now);
  return true;
}

void BusyArbiter::internal_meets_host(sim::Time now) {
  if (host_time_ == now) pull_low(now);
}

void BusyArbiter::pull_low(sim::Time now) {
  // Low now, high at the next MCLK edge: at most one MCLK period (delta spec 2.8).
  const sim::Time end = mclk_.time_of(period_index(now) + 1);
  scheduler_.cancel(release_event_);
  release_event_ = scheduler_.at(end, [this] { release(); });
  if (!busy_) {
    busy_ = true;
    drive_busyn_(true);
  }
}

void BusyArbiter::release() {
  release_event_ = {};
  busy_ = false;
  drive_busyn_(false);
}

void BusyArbiter::reset() {
  scheduler_.cancel(release_event_);
  release_event_ = {};
  std::fill(last_used_.begin(), last_used_.end(), -1);
  host_word_ = kNoWord;
  busy_ = false;
  drive_busyn_(false);
}

}  // namespace sercon::chip
