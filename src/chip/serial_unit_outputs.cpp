#include "sercon/chip/serial_unit_outputs.hpp"

#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"

namespace sercon::chip {
namespace {

std::size_t index_of_pin(unsigned pin) {
  if (pin < 1 || pin > SerialUnit::kTxdCount) {
    throw std::out_of_range("TxD" + std::to_string(pin) + ": the chip has TxD1..TxD6");
  }
  return pin - 1;
}

}  // namespace

void TxdOutputs::connect(unsigned pin, LineListener& listener) {
  Output& out = outputs_[index_of_pin(pin)];
  out.listener = &listener;
  sim::Time period = 0;
  const View& v = out.view;
  if (v.mode == Mode::Line) {
    const LineCondition c = line_condition_now(&period);
    listener.line_condition(unit_.chip().scheduler().now(), c, period);
  } else {
    listener.line_condition(unit_.chip().scheduler().now(), v.condition, v.period);
  }
}

void TxdOutputs::disconnect(unsigned pin) { outputs_[index_of_pin(pin)].listener = nullptr; }

LineCondition TxdOutputs::line_condition_now(sim::Time* period) const {
  *period = line_period_;
  return line_in_burst_ ? LineCondition::Idle : line_;
}

void TxdOutputs::line_condition(LineCondition condition, sim::Time period) {
  const sim::Time now = unit_.chip().scheduler().now();
  if (line_in_burst_ && now >= line_end_) line_in_burst_ = false;
  if (!line_in_burst_ && line_ == condition && line_period_ == period) return;
  const bool pins_change = (line_ == LineCondition::Dark) != (condition == LineCondition::Dark);
  line_ = condition;
  line_period_ = period;
  line_in_burst_ = false;
  for (Output& out : outputs_) {
    if (out.view.mode == Mode::Line && out.listener) {
      out.listener->line_condition(now, condition, period);
    }
  }
  if (pins_change) set_pins_following_line();
}

void TxdOutputs::line_burst(const LineBurst& burst) {
  const bool pins_change = line_ == LineCondition::Dark;
  line_ = LineCondition::Idle;  // what follows the burst
  line_period_ = burst.bit_period;
  line_in_burst_ = true;
  line_end_ = burst.end();
  for (Output& out : outputs_) {
    if (out.view.mode == Mode::Line && out.listener) out.listener->line_burst(burst);
  }
  if (pins_change) set_pins_following_line();
}

TxdOutputs::View TxdOutputs::view_of(unsigned pin) const {
  Chip& chip = unit_.chip();
  const RegisterFile& regs = chip.regs();
  const SerialFields& f = unit_.fields();
  View v;
  if (!unit_.running()) return v;  // reset: high impedance (TXOE = 0)
  const auto bit = [](std::uint16_t field, unsigned n) {
    return ((unsigned{field} >> n) & 1u) != 0;
  };
  if (pin >= 2 && bit(f.portsel.get(regs), pin - 2)) {
    // Port mode (datasheet Table 1: high impedance is a feature of the data function).
    v.mode = Mode::Port;
    const bool high = bit(f.portval.get(regs), pin - 2);
    v.condition = high != f.poltxd.on(regs) ? LineCondition::Light : LineCondition::Dark;
    return v;
  }
  if (!bit(f.txoe.get(regs), pin - 1)) return v;
  if (!f.txlight.on(regs)) {
    v.mode = Mode::Dark;
    return v;
  }
  switch (chip.test_mode()) {
    case TestMode::ContinuousLight:
      v.mode = Mode::Light;
      v.condition = LineCondition::Light;
      return v;
    case TestMode::ZeroBitStream:
      v.mode = Mode::ZeroBits;
      v.condition = LineCondition::ZeroBits;
      v.period = unit_.bit_period();
      return v;
    case TestMode::None:
      break;
  }
  v.mode = Mode::Line;
  return v;
}

sim::Level TxdOutputs::pin_level(const View& v) const {
  const RegisterFile& regs = unit_.chip().regs();
  const SerialFields& f = unit_.fields();
  if (v.mode == Mode::HighZ) return sim::Level::HighZ;
  if (v.mode == Mode::Port) {
    return sim::level_of((v.condition == LineCondition::Light) != f.poltxd.on(regs));
  }
  // A line with edges is not drawn bit by bit: the pin shows the light level while there
  // is a signal, the dark level while there is none.
  const bool dark = v.mode == Mode::Dark || (v.mode == Mode::Line && line_ == LineCondition::Dark);
  return sim::level_of(!dark != f.poltxd.on(regs));
}

void TxdOutputs::show(unsigned pin, const View& v) {
  Output& out = outputs_[pin - 1];
  unit_.chip().set_output(txd_pin(pin), pin_level(v));
  if (out.view == v) return;
  out.view = v;
  if (!out.listener) return;
  const sim::Time now = unit_.chip().scheduler().now();
  if (v.mode == Mode::Line) {
    sim::Time period = 0;
    const LineCondition c = line_condition_now(&period);
    out.listener->line_condition(now, c, period);
  } else {
    out.listener->line_condition(now, v.condition, v.period);
  }
}

void TxdOutputs::refresh() {
  for (unsigned pin = 1; pin <= SerialUnit::kTxdCount; ++pin) show(pin, view_of(pin));
}

void TxdOutputs::set_pins_following_line() {
  for (unsigned pin = 1; pin <= SerialUnit::kTxdCount; ++pin) {
    const View& v = outputs_[pin - 1].view;
    if (v.mode == Mode::Line) unit_.chip().set_output(txd_pin(pin), pin_level(v));
  }
}

}  // namespace sercon::chip
