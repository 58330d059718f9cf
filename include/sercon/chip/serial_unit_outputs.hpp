// TxD1-6: what each pin shows and what the fibre or bus behind it gets (datasheet Table 1:
// TxD1 data with high impedance; TxD2-6 data or parallel output port, each with individual
// high impedance; register 0x02 TXOE / TXLIGHT / TMODE, 0x0B PORTSEL / PORTVAL, 0x01 POLTXD).
//
// Listeners are told light: the line model carries what the fibre carries. POLTXD only
// decides which pin level is light (docs/serial-and-ring.md, "Polarity").
#pragma once

#include <array>

#include "sercon/chip/line.hpp"
#include "sercon/sim/signal.hpp"
#include "sercon/sim/time.hpp"

namespace sercon::chip {

class SerialUnit;

class TxdOutputs {
 public:
  explicit TxdOutputs(SerialUnit& unit) : unit_(unit) {}

  void connect(unsigned pin, LineListener& listener);  // pin 1..6
  void disconnect(unsigned pin);

  // The serial line (own telegrams, idle fill or the repeated signal) changes now.
  // Saying the condition the line is already in again is a no-op.
  void line_condition(LineCondition condition, sim::Time period);
  void line_burst(const LineBurst& burst);  // burst.start == now

  // Registers, test mode, polarity, clocks or reset state changed: re-derive every pin and
  // tell the listeners whose view changed.
  void refresh();

  // What the line is in now, for a listener that joins: mid-telegram counts as idle fill.
  LineCondition line_condition_now(sim::Time* period) const;

 private:
  enum class Mode : std::uint8_t { HighZ, Port, Dark, Light, ZeroBits, Line };
  struct View {  // what a listener is shown
    Mode mode = Mode::HighZ;
    LineCondition condition = LineCondition::Dark;  // for modes other than Line
    sim::Time period = 0;
    friend bool operator==(const View&, const View&) = default;
  };
  struct Output {
    LineListener* listener = nullptr;
    View view;
  };

  View view_of(unsigned pin) const;
  sim::Level pin_level(const View& view) const;
  void show(unsigned pin, const View& view);
  void set_pins_following_line();

  SerialUnit& unit_;
  std::array<Output, 6> outputs_{};
  // The serial line: a condition, or a burst until line_end_ (then Idle at its rate).
  LineCondition line_ = LineCondition::Dark;
  sim::Time line_period_ = 0;
  bool line_in_burst_ = false;
  sim::Time line_end_ = 0;
};

}  // namespace sercon::chip
