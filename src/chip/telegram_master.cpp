#include "sercon/chip/telegram_master.hpp"

#include <array>

#include "sercon/chip/serial_unit_transmitter.hpp"
#include "sercon/chip/telegram_header.hpp"

namespace sercon::chip {

MasterMst::MasterMst(TimeBase& time_base, Interrupts& interrupts, SerialUnit& serial,
                     TelegramRam& ram)
    : time_base_(time_base),
      regs_(time_base.regs()),
      interrupts_(interrupts),
      serial_(serial),
      ram_(ram),
      phas0_(field_ref("PHAS0", regs_.variant())),
      tcycdel_(field_ref("TCYCDEL", regs_.variant())),
      jtrdel1_(field_ref("JTRDEL1", regs_.variant())),
      jtrdel2_(field_ref("JTRDEL2", regs_.variant())) {}

// Counted before the raise: a handler run from the INT0 / INT1 callback reads NMSTERR.
void MasterMst::error() {
  ram_.count_error(telegram::kNmsterr);
  interrupts_.raise(Irq::RetMst);
}

bool MasterMst::send() {
  if (out_ && !judged_) error();  // the last one never came back, and had no window
  out_ = false;
  time_base_.cancel(window_end_);
  window_end_ = {};
  const sim::Time now = time_base_.scheduler().now();
  // The transmitter itself (SerialUnit's send and transmit_free_at are calls into it).
  if (serial_.bit_period() == 0 || serial_.next_bit_edge(now) < serial_.transmitter().free_at()) {
    ram_.count_error(telegram::kNmsterr);
    return false;
  }
  const std::array<std::uint8_t, 1> phase{static_cast<std::uint8_t>(phas0_.get(regs_))};
  serial_.transmitter().send(now, 0xFF, phase);
  out_ = true;
  judged_ = false;
  if (jtrdel2_.get(regs_) != 0) {
    window_end_ = time_base_.at_cycle_time(
        jtrdel2_.get(regs_), [](void* mst) { static_cast<MasterMst*>(mst)->window_ends(); }, this);
  }
  return true;
}

void MasterMst::window_ends() {
  window_end_ = {};
  if (!out_ || judged_) return;
  judged_ = true;
  error();
}

void MasterMst::returned() {
  if (!out_) return;  // none of this cycle's is out: sent none, or it is back already
  out_ = false;
  time_base_.cancel(window_end_);
  window_end_ = {};
  // Measured whenever it comes back, even after the window closed on it: a driver whose
  // ring delay grew past JTRDEL2 reads the new delay here to move the window.
  const std::uint16_t at = time_base_.tcnt();
  tcycdel_.put(regs_, at);
  if (judged_) return;  // counted missing when the window closed
  judged_ = true;
  const std::uint16_t last = jtrdel2_.get(regs_);
  if (last != 0 && (at < jtrdel1_.get(regs_) || at > last)) error();
}

}  // namespace sercon::chip
