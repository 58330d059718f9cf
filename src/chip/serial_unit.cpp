#include "sercon/chip/serial_unit.hpp"

#include "sercon/chip/chip.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/line_length.hpp"
#include "sercon/chip/serial_unit_monitor.hpp"
#include "sercon/chip/serial_unit_outputs.hpp"
#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"
#include "sercon/chip/serial_unit_transmitter.hpp"

namespace sercon::chip {

SerialUnit::SerialUnit(Chip& chip)
    : chip_(chip),
      fields_(chip.variant()),
      outputs_(std::make_unique<TxdOutputs>(*this)),
      transmitter_(std::make_unique<SerialTransmitter>(*this)),
      receiver_(std::make_unique<SerialReceiver>(*this)),
      repeater_(std::make_unique<SerialRepeater>(*this)),
      monitor_(std::make_unique<LineMonitor>(*this)) {
  chip.regs().on_change([this](std::uint8_t address) { on_register_change(address); });
  // TM0/TM1 choose the test generator unless TMODE2 overrides them (delta spec 2.3.3).
  for (const Pin p : {Pin::TM0, Pin::TM1}) {
    chip.pin(p).react([this](sim::Level) {
      if (running_) outputs_->refresh();
    });
  }
}

SerialUnit::~SerialUnit() = default;

void SerialUnit::reset(ResetCause) {
  receiver_->absorb_lazy();  // at the rate and settings they were passed on with
  running_ = false;
  set_bit_period(0);
  receiver_->refresh_hop_period();
  transmitter_->reset();
  receiver_->reset();
  monitor_->reset();
  outputs_->refresh();  // TxD1-6 high impedance: listeners see Dark
  repeater_->reset();
}

void SerialUnit::release() {
  running_ = true;
  set_bit_period(compute_bit_period());
  receiver_->refresh_hop_period();
  repon_ = fields_.repon.on(chip_.regs());
  poltxd_ = fields_.poltxd.on(chip_.regs());
  control_ = control_bits();
  transmitter_->release();
  repeater_->release();
  outputs_->refresh();
  monitor_->release();
  receiver_->release();
}

sim::Time SerialUnit::compute_bit_period() const {
  const std::int64_t hz = chip_.serial_clocks().bit_rate_hz;
  return hz > 0 ? sim::period_of_hz(hz) : 0;
}

std::uint16_t SerialUnit::control_bits() const {
  const auto status =
      static_cast<std::uint16_t>(fields_.rdist.mask | fields_.fibbr.mask | fields_.recact.mask);
  return static_cast<std::uint16_t>(chip_.regs().value(fields_.txoe.address) & ~status);
}

// Status bits this unit sets itself (RDIST, FIBBR) also land here: they change
// nothing and return early, so a telegram costs no output refresh.
void SerialUnit::on_register_change(std::uint8_t address) {
  if (!running_) return;
  const RegisterFile& regs = chip_.regs();
  if (address == fields_.repon.address) {
    receiver_->absorb_lazy();  // at the rate and settings they were passed on with
    const sim::Time period = compute_bit_period();
    const bool repon = fields_.repon.on(regs);
    const bool poltxd = fields_.poltxd.on(regs);
    if (period == bit_period_ && repon == repon_ && poltxd == poltxd_) return;
    const bool rate_changed = period != bit_period_;
    set_bit_period(period);
    receiver_->refresh_hop_period();
    repon_ = repon;
    poltxd_ = poltxd;
    if (rate_changed) receiver_->refresh_rate();
    repeater_->refresh();
    outputs_->refresh();
    if (rate_changed) monitor_->refresh_limits();
  } else if (address == fields_.txoe.address) {
    const std::uint16_t control = control_bits();
    if (control == control_) return;
    control_ = control;
    outputs_->refresh();
    monitor_->refresh_line_error();
  } else if (address == fields_.portsel.address) {
    outputs_->refresh();
  } else if (address == fields_.rdistlim.address) {
    monitor_->refresh_limits();
  }
}

sim::Time SerialUnit::send(sim::Time start, std::uint8_t address,
                           std::span<const std::uint8_t> data) {
  return transmitter_->send(start, address, data);
}

sim::Time SerialUnit::burst_duration(std::uint8_t address,
                                     std::span<const std::uint8_t> data) const {
  return static_cast<sim::Time>(telegram_line_bits(address, data)) * bit_period_;
}

sim::Time SerialUnit::transmit_free_at() const { return transmitter_->free_at(); }

void SerialUnit::on_telegram_start(TelegramStartHandler handler) {
  receiver_->on_start(std::move(handler));
}

void SerialUnit::on_telegram(TelegramHandler handler) {
  receiver_->on_telegram(std::move(handler));
}

void SerialUnit::on_telegram_start(void* context, TelegramStartFn handler) {
  receiver_->on_start(context, handler);
}

void SerialUnit::on_telegram(void* context, TelegramFn handler) {
  receiver_->on_telegram(context, handler);
}

void SerialUnit::set_interest(const ReceiveInterest* interest) {
  receiver_->set_interest(interest);
}

void SerialUnit::interest_changed() { receiver_->interest_changed(); }

void SerialUnit::set_lazy_hops(bool on) { receiver_->set_lazy_hops(on); }

std::uint64_t SerialUnit::lazy_hops_taken() const { return receiver_->lazy_hops_taken(); }

sim::Time SerialUnit::repeated_at(sim::Time arrival) const {
  return repeater_->forward_time(arrival);
}

LineListener& SerialUnit::rxd() { return *receiver_; }

void SerialUnit::connect_txd(unsigned pin, LineListener& listener) {
  outputs_->connect(pin, listener);
}

void SerialUnit::disconnect_txd(unsigned pin) { outputs_->disconnect(pin); }

std::size_t SerialUnit::decode_count() { return burst_decode_count(); }

}  // namespace sercon::chip
