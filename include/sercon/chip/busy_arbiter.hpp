// BUSYN (datasheet Table 1, 3.5.5/3.5.7; delta spec 2.8): when the µP touches a RAM word
// that the telegram processor uses in the same MCLK period, BUSYN goes low at once and
// high again at the end of that MCLK period, so it is never low for more than one MCLK.
// MCLK period k runs from MCLK edge k to edge k + 1 (MclkGrid). An internal access at the
// very instant of a µP access to the same word collides too, whichever of the two ran
// first: equal-time events run in no order the chip could know (Table 1: "simultaneously").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "sercon/chip/mclk_divider.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class BusyArbiter {
 public:
  // `drive_busyn(low)` sets the BUSYN pin; `ram_words` is the RAM's size.
  BusyArbiter(sim::Scheduler& scheduler, const MclkGrid& mclk, std::uint16_t ram_words,
              std::function<void(bool low)> drive_busyn);
  ~BusyArbiter();
  BusyArbiter(const BusyArbiter&) = delete;
  BusyArbiter& operator=(const BusyArbiter&) = delete;

  // The internal accesses' marks without a bounds check, for a port that checks its words
  // itself (Chip::TpRamPort): every word given must be < ram_words. Valid as long as the
  // arbiter.
  class Marks {
   public:
    void mark(std::uint16_t word) const {
      const sim::Time now = scheduler_->now();
      used_[word] = now;
      if (meets_host(now) && word == arbiter_->host_word_) arbiter_->internal_meets_host(now);
    }
    void mark_run(std::uint16_t first, std::size_t count) const {
      mark_run(first, count, [](std::size_t) {});
    }
    // Marks the run and calls each(i) for its words i = 0 .. count - 1, in one pass. Runs
    // are mostly a few words (container heads, short data): up to 3 go in straight-line
    // code, where a vectorised loop's set-up would cost more than the words. Not 4: a
    // fixed index 3 here made GCC report a false -Warray-bounds wherever a 3-word run
    // (a list item's TRT, TLEN, PT) is inlined along with TelegramRam's run past the RAM.
    template <typename Each>
    void mark_run(std::uint16_t first, std::size_t count, Each each) const {
      const sim::Time now = scheduler_->now();
      if (meets_host(now) && arbiter_->host_word_ - std::uint32_t{first} < count)
        arbiter_->internal_meets_host(now);
      sim::Time* used = used_ + first;
      const auto word = [&](std::size_t i) {
        used[i] = now;
        each(i);
      };
      switch (count) {
        case 0:
          return;
        case 1:
          word(0);
          return;
        case 2:
          word(0);
          word(1);
          return;
        case 3:
          word(0);
          word(1);
          word(2);
          return;
        default:
          for (std::size_t i = 0; i < count; ++i) word(i);
      }
    }

    // mark(word) and mark_run(first, count) at one instant: the time and the µP's word are
    // looked at once (an internal access meeting it twice at one instant pulls BUSYN low as
    // once, with nothing scheduled between). Straight-line up to 5 words in the run (a
    // receive container's control word, POS and 3 data words).
    void mark_word_and_run(std::uint16_t word, std::uint16_t first, std::size_t count) const {
      const sim::Time now = scheduler_->now();
      if (meets_host(now)) {
        const std::uint32_t host = arbiter_->host_word_;
        if (host == word || host - std::uint32_t{first} < count) arbiter_->internal_meets_host(now);
      }
      used_[word] = now;
      sim::Time* used = used_ + first;
      switch (count) {
        case 5:
          used[4] = now;
          [[fallthrough]];
        case 4:
          used[3] = now;
          [[fallthrough]];
        case 3:
          used[2] = now;
          [[fallthrough]];
        case 2:
          used[1] = now;
          [[fallthrough]];
        case 1:
          used[0] = now;
          [[fallthrough]];
        case 0:
          return;
        default:
          for (std::size_t i = 0; i < count; ++i) used[i] = now;
      }
    }

   private:
    friend class BusyArbiter;
    // The µP's last access was at this instant: only then can an internal access now meet
    // it (internal_meets_host). Asked first: mostly it was long ago, and the word need not
    // be compared.
    bool meets_host(sim::Time now) const { return arbiter_->host_time_ == now; }
    Marks(BusyArbiter* arbiter, sim::Time* used, const sim::Scheduler* scheduler)
        : arbiter_(arbiter), used_(used), scheduler_(scheduler) {}

    BusyArbiter* arbiter_;
    sim::Time* used_;
    const sim::Scheduler* scheduler_;
  };
  Marks marks() { return Marks(this, last_used_.data(), &scheduler_); }

  // The telegram processor uses `word` (< ram_words) now, in the current MCLK period.
  // Inline: a list walk makes hundreds of these per cycle.
  void internal_access(std::uint16_t word) {
    const sim::Time now = scheduler_.now();
    last_used_.at(word) = now;
    if (word == host_word_) internal_meets_host(now);
  }
  // The same for the `count` words from `first` (all < ram_words).
  void internal_access_run(std::uint16_t first, std::size_t count) {
    if (first + count > last_used_.size()) beyond_the_ram();
    marks().mark_run(first, count);
  }
  // The µP accesses `word` (< ram_words) now. Returns true when it collides and BUSYN
  // goes low.
  bool host_access(std::uint16_t word);
  bool busy() const { return busy_; }
  // BUSYN high, nothing remembered.
  void reset();

 private:
  Edge period_index(sim::Time t) const { return mclk_.last_at_or_before(t); }
  // BUSYN low from now to the end of the present MCLK period.
  void pull_low(sim::Time now);
  // An internal access to the word of the µP's last access: a collision if that was now.
  void internal_meets_host(sim::Time now);
  void release();
  [[noreturn]] static void beyond_the_ram();

  sim::Scheduler& scheduler_;
  MclkGrid mclk_;
  std::function<void(bool)> drive_busyn_;
  // Per RAM word: when the telegram processor last used it (-1: never). The time, not
  // its MCLK period: the period is worked out only for the rare µP access that asks
  // (same period iff same period index), so an internal access is one store.
  std::vector<sim::Time> last_used_;
  // The µP's last RAM access: its word (kNoWord: none) and instant.
  static constexpr std::uint32_t kNoWord = 0xFFFF'FFFFu;
  std::uint32_t host_word_ = kNoWord;
  sim::Time host_time_ = -1;
  bool busy_ = false;
  sim::Scheduler::EventId release_event_{};
};

}  // namespace sercon::chip
