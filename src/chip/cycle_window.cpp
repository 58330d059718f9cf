#include "sercon/chip/cycle_window.hpp"

#include <algorithm>
#include <utility>

namespace sercon::chip {
CycleWindow::CycleWindow(TimeBase& time_base, Interrupts& interrupts,
                         std::function<void()> closed_empty)
    : time_base_(time_base),
      interrupts_(interrupts),
      closed_empty_(std::move(closed_empty)),
      close_event_(time_base, this) {
  read_fields();
  time_base_.regs().on_change_first([this](std::uint8_t) { read_fields(); });
}

void CycleWindow::read_fields() {
  const RegisterFile& regs = time_base_.regs();
  jtscyc1_ = static_cast<std::int16_t>(regs.field_value(kJtscyc1));
  jtscyc2_ = static_cast<std::int16_t>(regs.field_value(kJtscyc2));
}

void CycleWindow::closes(void* window) { static_cast<CycleWindow*>(window)->close(); }

// The slave's free-wheel first: a handler run from the INT0 / INT1 callback of
// INT_MSTMISS reads the substitute cycle's counter.
void CycleWindow::close() {
  state_ = State::Missed;
  closed_empty_();
  interrupts_.raise(Irq::MstMiss);
}

// Delta spec 2.6.5: a CYC_CLK "not inside this window" sets MSTEARLY; after an empty
// window it also is late. A master has no substitute window to be in.
void CycleWindow::missed_judged(bool master, std::int64_t position) {
  if (master) {
    interrupts_.raise(Irq::MstEarly);
    interrupts_.raise(Irq::MstLate);
  } else if (position < opens_) {
    interrupts_.raise(Irq::MstLate);
  }
}

}  // namespace sercon::chip
