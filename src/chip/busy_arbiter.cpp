#include "sercon/chip/busy_arbiter.hpp"

#include <algorithm>
#include <stdexcept>

namespace sercon::chip {

BusyArbiter::BusyArbiter(sim::Scheduler& scheduler, sim::Time mclk_period,
                         std::function<void(bool)> drive_busyn)
    : scheduler_(scheduler), mclk_period_(mclk_period), drive_busyn_(std::move(drive_busyn)) {
  if (mclk_period_ <= 0) throw std::invalid_argument("BusyArbiter: MCLK period must be > 0");
}

BusyArbiter::~BusyArbiter() { scheduler_.cancel(release_event_); }

void BusyArbiter::internal_access(std::uint16_t word) {
  const auto period = period_index(scheduler_.now());
  if (period != words_period_) {
    words_.clear();
    words_period_ = period;
  }
  if (std::find(words_.begin(), words_.end(), word) == words_.end()) words_.push_back(word);
}

bool BusyArbiter::host_access(std::uint16_t word) {
  const sim::Time now = scheduler_.now();
  const auto period = period_index(now);
  if (period != words_period_ || std::find(words_.begin(), words_.end(), word) == words_.end()) {
    return false;
  }
  // Low now, high at the next MCLK edge: at most one MCLK period (delta spec 2.8).
  const sim::Time end = (period + 1) * mclk_period_;
  scheduler_.cancel(release_event_);
  release_event_ = scheduler_.at(end, [this] { release(); });
  if (!busy_) {
    busy_ = true;
    drive_busyn_(true);
  }
  return true;
}

void BusyArbiter::release() {
  release_event_ = {};
  busy_ = false;
  drive_busyn_(false);
}

void BusyArbiter::reset() {
  scheduler_.cancel(release_event_);
  release_event_ = {};
  words_.clear();
  words_period_ = -1;
  busy_ = false;
  drive_busyn_(false);
}

}  // namespace sercon::chip
