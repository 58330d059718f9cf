#include "sercon/chip/cycle_window.hpp"

#include <algorithm>
#include <utility>

namespace sercon::chip {
namespace {

constexpr std::uint8_t kJtscyc1 = 0x15;
constexpr std::uint8_t kJtscyc2 = 0x16;

std::int64_t signed16(std::uint16_t value) { return static_cast<std::int16_t>(value); }

}  // namespace

CycleWindow::CycleWindow(TimeBase& time_base, Interrupts& interrupts,
                         std::function<void()> closed_empty)
    : time_base_(time_base),
      interrupts_(interrupts),
      closed_empty_(std::move(closed_empty)),
      close_event_(time_base) {}

// TSCYC = 0 means the cycle time is not programmed: nothing is expected, so no window
// closes empty and nothing free-wheels.
void CycleWindow::expect_next(const CycleStart& start) {
  forget();
  tscyc_ = start.tscyc;
  if (tscyc_ == 0) return;
  const RegisterFile& regs = time_base_.regs();
  opens_ = tscyc_ + signed16(regs.value(kJtscyc1));
  closes_ = tscyc_ + signed16(regs.value(kJtscyc2));
  state_ = start.kind == CycleKind::Substitute ? State::Missed : State::Synced;
  // A window programmed to close before the counter's start closes at the first step.
  time_base_.at_cycle_time(close_event_, std::max(closes_, start.count), &CycleWindow::closes,
                           this);
}

void CycleWindow::closes(void* window) {
  auto& w = *static_cast<CycleWindow*>(window);
  w.close_event_.forget();
  w.close();
}

void CycleWindow::forget() {
  time_base_.cancel(close_event_.id());
  close_event_.forget();
  state_ = State::Unsynced;
}

// The slave's free-wheel first: a handler run from the INT0 / INT1 callback of
// INT_MSTMISS reads the substitute cycle's counter.
void CycleWindow::close() {
  state_ = State::Missed;
  closed_empty_();
  interrupts_.raise(Irq::MstMiss);
}

void CycleWindow::judge(bool master) {
  // Mostly the close is still ahead: its time is looked at before the scheduler is asked.
  if (close_event_.when() <= time_base_.scheduler().now() &&
      time_base_.when(close_event_.id()).has_value()) {
    time_base_.cancel(close_event_.id());
    close_event_.forget();
    close();
  }
  const std::int64_t position = time_base_.count();
  switch (state_) {
    case State::Unsynced:
      return;
    case State::Synced:
      if (position < opens_) interrupts_.raise(Irq::MstEarly);
      return;
    case State::Missed:
      // Delta spec 2.6.5: a CYC_CLK "not inside this window" sets MSTEARLY; after an
      // empty window it also is late. A master has no substitute window to be in.
      if (master) {
        interrupts_.raise(Irq::MstEarly);
        interrupts_.raise(Irq::MstLate);
      } else if (position < opens_) {
        interrupts_.raise(Irq::MstLate);
      }
      return;
  }
}

}  // namespace sercon::chip
