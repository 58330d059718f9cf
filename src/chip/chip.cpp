#include "sercon/chip/chip.hpp"

#include <stdexcept>
#include <string>

namespace sercon::chip {
namespace {

using sim::Level;

// Register 0x01 (SERMODE) and 0x02 (SERCTRL) addresses, from the register table.
constexpr std::uint8_t kSerMode = 0x01;
constexpr std::uint8_t kSerCtrl = 0x02;

std::uint16_t mask_of(std::string_view field, Variant variant) {
  const auto f = find_field(field, variant);
  return f ? f->mask() : std::uint16_t{0};
}

unsigned lsb_of(std::string_view field, Variant variant) {
  const auto f = find_field(field, variant);
  return f ? f->lsb : 0u;
}

const ChipConfig& validated(const ChipConfig& config) {
  config.validate();
  return config;
}

// Level of every output right after reset (the inactive level with the reset polarities
// of the register table: INT0/INT1, CON_CLK, DIV_CLK active high; TXOE = 0 puts TxD1-6
// into high impedance). Pin 24 is WDOGN on the 816 only; the 410B's TxDNRZ there (delta
// spec 2.2 names it, nothing describes it) is not modelled and floats.
Level reset_output_level(Pin p, Variant v) {
  switch (p) {
    case Pin::WDOGN:
      return v == Variant::Sercon410B ? Level::HighZ : Level::High;
    case Pin::BUSYN:
    case Pin::RECACTN:
    case Pin::IDLE:
    case Pin::L_ERRN:
      return Level::High;
    case Pin::TxD1:
    case Pin::TxD2:
    case Pin::TxD3:
    case Pin::TxD4:
    case Pin::TxD5:
    case Pin::TxD6:
      return Level::HighZ;
    default:
      return Level::Low;
  }
}

// Level of every input when the chip is built: the straps from the config, everything
// else inactive (not in reset, no chip select, no strobe, Intel bus, no address latch).
Level initial_input_level(Pin p, const ChipConfig& c) {
  switch (p) {
    case Pin::SBAUD:
      return sim::level_of(c.sbaud);
    case Pin::SBAUD16:
      return sim::level_of(c.sbaud16);
    case Pin::TM0:
      return sim::level_of(c.tm0);
    case Pin::TM1:
      return sim::level_of(c.tm1);
    case Pin::BUSWIDTH:
      return sim::level_of(c.buswidth);
    case Pin::BYTEDIR:
      return sim::level_of(c.bytedir);
    case Pin::RSTN:
    case Pin::MCSN0:
    case Pin::MCSN1:
    case Pin::PCSN0:
    case Pin::RDN:
    case Pin::WRN:
    case Pin::BHEN:
    case Pin::ALEL:  // datasheet Table 1: tied to VDD when ADMUX = 0
    case Pin::ALEH:
    case Pin::DMAACKRN:
    case Pin::DMAACKTN:
      return Level::High;
    default:
      return Level::Low;
  }
}

Level initial_level(Pin p, const ChipConfig& c) {
  switch (pin_info(p).direction) {
    case PinDirection::Out:
      return reset_output_level(p, c.variant);
    case PinDirection::In:
      return initial_input_level(p, c);
    case PinDirection::InOut:
      break;
  }
  // Data lines float (pull-ups); address lines start at 0, driven by the board.
  return p <= Pin::D15 ? Level::HighZ : Level::Low;
}

}  // namespace

Chip::Chip(sim::Scheduler& scheduler, const ChipConfig& config)
    : scheduler_(scheduler),
      config_(validated(config)),
      mclk_(config_.mclk_hz),
      regs_(config.variant),
      ram_(ram_words_of(config.variant)),
      output_levels_(kPinCount, Level::Low),
      chip_drives_(kPinCount, false),
      busy_(scheduler, mclk_, ram_words_of(config.variant),
            [this](bool low) { set_output(Pin::BUSYN, !low); }) {
  pins_.reserve(kPinCount);
  for (std::size_t i = 0; i < kPinCount; ++i) {
    const Pin p = pin_at(i);
    pins_.emplace_back(std::string(pin_name(p)), initial_level(p, config_));
    if (pin_info(p).direction == PinDirection::Out) {
      output_levels_[i] = pins_[i].level();
      chip_drives_[i] = true;
    }
  }
  watch_pins();
  regs_.on_write(kSerMode, [this](std::uint16_t written, std::uint16_t) {
    if (written & mask_of("SWRST", variant())) software_reset();
  });
  build_units();
  enter_reset(ResetCause::PowerOn);
  leave_reset();
}

Chip::~Chip() = default;

void Chip::watch_pins() {
  pin(Pin::RSTN).react([this](Level) {
    const bool low = !input_high(Pin::RSTN);
    if (low == rstn_low_) return;
    const bool was_in_reset = in_reset();
    rstn_low_ = low;
    if (low && !was_in_reset) enter_reset(ResetCause::Pin);
    if (!low && !in_reset()) leave_reset();
  });
  pin(Pin::OUTZ).react([this](Level) {
    const bool high = input_high(Pin::OUTZ);
    if (high == outz_) return;
    const bool was_in_reset = in_reset();
    outz_ = high;
    refresh_outputs();
    if (high && !was_in_reset) enter_reset(ResetCause::OutputsZ);
    if (!high && !in_reset()) leave_reset();
  });
  // Delta spec 2.3.3: TM0/TM1 set REPON only while the chip is in reset.
  for (Pin p : {Pin::TM0, Pin::TM1}) {
    pin(p).react([this](Level) {
      if (in_reset()) apply_pin_reset_bits();
    });
  }
  for (Pin p : {Pin::SBAUD, Pin::SBAUD16}) {
    pin(p).react([this](Level) { refresh_pin_status_bits(); });
  }
}

// --- reset ----------------------------------------------------------------------------

void Chip::enter_reset(ResetCause cause) {
  last_reset_ = cause;
  regs_.reset();  // RSTFL's reset value is 1: every reset sets it
  apply_pin_reset_bits();
  refresh_pin_status_bits();
  busy_.reset();
  for (std::size_t i = 0; i < kPinCount; ++i) {
    const Pin p = pin_at(i);
    const PinDirection dir = pin_info(p).direction;
    // D15-0 and A15-0 belong to the bus interface (PinBus, DmaPort), whose resets release
    // D15-0; BUSYN and NDTRO (combinational) are driven by their owners without a glitch.
    if (dir == PinDirection::Out && p != Pin::BUSYN && p != Pin::NDTRO) {
      set_output(p, reset_output_level(p, variant()));
    }
  }
  for (auto& u : units_) u->reset(cause);
}

void Chip::leave_reset() {
  for (auto& u : units_) u->release();
}

void Chip::software_reset() {
  if (in_reset()) return;
  sim::Signal::batch([this] {
    enter_reset(ResetCause::Software);
    leave_reset();
  });
}

void Chip::apply_pin_reset_bits() {
  // REPON's pin-dependent reset value exists on the 816 only (delta spec 2.3.3).
  if (variant() != Variant::Sercon816) return;
  const bool on = repon_after_reset(input_high(Pin::TM0), input_high(Pin::TM1));
  regs_.set_bits(kSerMode, mask_of("REPON", variant()), on);
}

void Chip::refresh_pin_status_bits() {
  regs_.set_bits(kSerMode, mask_of("SREGEN", variant()), input_high(Pin::SBAUD16));
  regs_.set_bits(kSerMode, mask_of("SBAUD", variant()), input_high(Pin::SBAUD));
}

// --- pins -----------------------------------------------------------------------------

void Chip::drive(Pin p, Level level) {
  const PinInfo& info = pin_info(p);
  const std::string name(info.name);
  const std::size_t i = index_of(p);
  if (info.direction == PinDirection::Out) {
    throw std::invalid_argument(name + " is an output of the chip; the board cannot drive it");
  }
  if (info.direction == PinDirection::InOut && chip_drives_[i] && !outz_) {
    throw std::invalid_argument(name + " is driven by the chip now (bus read or ADMUX = 1)");
  }
  if (p == Pin::MCLK || p == Pin::SCLK) {
    throw std::invalid_argument(name + " is modelled by its frequency in ChipConfig, not edges");
  }
  if (level == Level::HighZ && info.pull == Pull::None) {
    throw std::invalid_argument(name + " has no internal pull resistor and cannot float");
  }
  const bool high = level == Level::High || (level == Level::HighZ && info.pull == Pull::Up);
  if (p == Pin::TEST && high) {
    throw std::invalid_argument("TEST must be tied low (datasheet Table 1)");
  }
  if (p == Pin::SBAUD16 && !high) {
    if (variant() == Variant::Sercon410B) {
      throw std::invalid_argument(
          "SREGEN = 0 selects external clock recovery on the 410B, which is not modelled");
    }
    if (config_.sclk_hz < 32'000'000) {
      throw std::invalid_argument("SBAUD16 = 0 turns the PLL on, which needs SCLK >= 32 MHz");
    }
  }
  pins_[i].set(level);
}

bool Chip::input_high(Pin p) const {
  const Level level = pin(p).level();
  if (level == Level::HighZ) return pin_info(p).pull == Pull::Up;
  return level == Level::High;
}

void Chip::set_output(Pin p, Level level) {
  const PinInfo& info = pin_info(p);
  if (info.direction == PinDirection::In) {
    throw std::logic_error("Chip::set_output: " + std::string(info.name) + " is an input");
  }
  const std::size_t i = index_of(p);
  output_levels_[i] = level;
  if (info.direction == PinDirection::InOut) chip_drives_[i] = level != Level::HighZ;
  if (info.direction == PinDirection::InOut && !chip_drives_[i]) {
    pins_[i].set(Level::HighZ);
    return;
  }
  // Datasheet Table 1: OUTZ = 1 puts every output into high impedance, except NDTRO.
  pins_[i].set(outz_ && p != Pin::NDTRO ? Level::HighZ : level);
}

void Chip::refresh_outputs() {
  for (std::size_t i = 0; i < kPinCount; ++i) {
    if (!chip_drives_[i]) continue;
    const Pin p = pin_at(i);
    pins_[i].set(outz_ && p != Pin::NDTRO ? Level::HighZ : output_levels_[i]);
  }
}

// --- clocks and modes -----------------------------------------------------------------

sim::Time Chip::next_mclk_edge(sim::Time t) const {
  return mclk_.time_of(mclk_.first_at_or_after(t));
}

SerialClocks Chip::serial_clocks() const {
  if (outz_) return SerialClocks{};  // Table 1: OUTZ = 1 turns the clocks off
  const Variant v = variant();
  SerialClockSelect s;
  s.variant = v;
  s.sclk_hz = config_.sclk_hz;
  s.sbaud = input_high(Pin::SBAUD);
  s.sbaud16 = input_high(Pin::SBAUD16);
  s.entsbaud = regs_.bit(kSerMode, mask_of("ENTSBAUD", v));
  s.swbaud = regs_.bit(kSerMode, mask_of("SWBAUD", v));
  s.swbaud16 = regs_.bit(kSerMode, mask_of("SWBAUD16", v));
  return chip::serial_clocks(s);
}

TestMode Chip::test_mode() const {
  const Variant v = variant();
  const auto tmode = static_cast<std::uint16_t>((regs_.value(kSerCtrl) & mask_of("TMODE", v)) >>
                                                lsb_of("TMODE", v));
  return effective_test_mode(input_high(Pin::TM0), input_high(Pin::TM1), tmode);
}

// --- µP bus ---------------------------------------------------------------------------

BusResult Chip::bus(const BusCycle& cycle) { return access(cycle, true); }

bool Chip::write_strobe_starts(const BusCycle& cycle) {
  if (outz_ || decode_target(cycle) != BusTarget::Ram) return false;
  const ByteLanes lanes =
      byte_lanes(input_high(Pin::BUSWIDTH), input_high(Pin::BYTEDIR), cycle.address, cycle.bhen);
  if (lanes.word_mask() == 0) return false;  // no byte lane: no word is touched
  return busy_.host_access(ram_word(cycle.address, ram_.size()));
}

BusResult Chip::write_strobe_ends(const BusCycle& cycle) {
  BusCycle c = cycle;
  c.write = true;
  return access(c, false);  // the collision was the strobe start's question
}

// One batch of signal changes (sim/signal.hpp): the pins an access moves (INT0/1 after a
// W1C, outputs after a mode write) are heard once the chip has taken the whole access.
BusResult Chip::access(const BusCycle& cycle, bool ask_busy) {
  return sim::Signal::batch([&] { return take_access(cycle, ask_busy); });
}

BusResult Chip::take_access(const BusCycle& cycle, bool ask_busy) {
  const BusTarget target = decode_target(cycle);
  if (target == BusTarget::Both) {
    throw std::invalid_argument(
        "bus cycle selects RAM (MCSN0 = MCSN1 = 0) and registers (PCSN0 = 0, PCS1 = 1) at "
        "once; both would drive D15-0");
  }
  BusResult result;
  result.target = target;
  if (outz_ || target == BusTarget::None) return result;  // D15-0 float, writes ignored
  const ByteLanes lanes =
      byte_lanes(input_high(Pin::BUSWIDTH), input_high(Pin::BYTEDIR), cycle.address, cycle.bhen);
  return target == BusTarget::Ram ? ram_cycle(cycle, lanes, ask_busy)
                                  : register_cycle(cycle, lanes);
}

BusResult Chip::ram_cycle(const BusCycle& cycle, const ByteLanes& lanes, bool ask_busy) {
  BusResult result;
  result.target = BusTarget::Ram;
  const std::uint16_t mask = lanes.word_mask();
  if (mask == 0) return result;  // 16-bit bus, A0 = 1 and BHEN = 1: no byte lane
  const std::uint16_t word = ram_word(cycle.address, ram_.size());
  result.busy = ask_busy && busy_.host_access(word);
  result.driven = lanes.data_mask();
  if (cycle.write) {
    ram_.write(word, lanes.to_word(cycle.data), mask);
  } else {
    result.data = static_cast<std::uint16_t>(lanes.to_data(ram_.read(word)) | ~result.driven);
  }
  return result;
}

BusResult Chip::register_cycle(const BusCycle& cycle, const ByteLanes& lanes) {
  BusResult result;
  result.target = BusTarget::Registers;
  const std::uint16_t mask = lanes.word_mask();
  if (mask == 0) return result;
  const auto reg = static_cast<std::uint8_t>(register_word(cycle.address));
  result.driven = lanes.data_mask();
  if (cycle.write) {
    // Held in reset (RSTN = 0): the registers keep their reset values.
    if (!in_reset()) regs_.bus_write(reg, lanes.to_word(cycle.data), mask);
  } else {
    result.data = static_cast<std::uint16_t>(lanes.to_data(regs_.bus_read(reg)) | ~result.driven);
  }
  return result;
}

std::uint16_t Chip::bus_word_read(const BusCycle& base) {
  const bool bus16 = input_high(Pin::BUSWIDTH);
  const bool bytedir = input_high(Pin::BYTEDIR);
  std::uint16_t word = 0;
  for (unsigned half = 0; half < (bus16 ? 1u : 2u); ++half) {
    BusCycle c = base;
    c.write = false;
    c.bhen = false;
    c.address = static_cast<std::uint16_t>((base.address & ~1u) | half);
    const BusResult r = bus(c);
    word |= byte_lanes(bus16, bytedir, c.address, c.bhen).to_word(r.data);
  }
  return word;
}

void Chip::bus_word_write(const BusCycle& base, std::uint16_t value) {
  const bool bus16 = input_high(Pin::BUSWIDTH);
  const bool bytedir = input_high(Pin::BYTEDIR);
  for (unsigned half = 0; half < (bus16 ? 1u : 2u); ++half) {
    BusCycle c = base;
    c.write = true;
    c.bhen = false;
    c.address = static_cast<std::uint16_t>((base.address & ~1u) | half);
    c.data = byte_lanes(bus16, bytedir, c.address, c.bhen).to_data(value);
    bus(c);
  }
}

namespace {

BusCycle register_select(std::uint16_t word_address) {
  if (word_address > 0x3F) {
    throw std::out_of_range("register word address " + std::to_string(word_address) +
                            " is beyond A6-1 (0x00..0x3F)");
  }
  BusCycle c;
  c.pcsn0 = false;
  c.pcs1 = true;
  c.address = static_cast<std::uint16_t>(word_address * 2u);
  return c;
}

BusCycle ram_select(std::uint16_t word_address, std::uint16_t ram_words) {
  if (word_address >= ram_words) {
    throw std::out_of_range("RAM word address " + std::to_string(word_address) + " is beyond the " +
                            std::to_string(ram_words) + "-word RAM");
  }
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.address = static_cast<std::uint16_t>(word_address * 2u);
  return c;
}

}  // namespace

std::uint16_t Chip::reg_read(std::uint16_t word_address) {
  return bus_word_read(register_select(word_address));
}

void Chip::reg_write(std::uint16_t word_address, std::uint16_t value) {
  bus_word_write(register_select(word_address), value);
}

std::uint16_t Chip::ram_read(std::uint16_t word_address) {
  return bus_word_read(ram_select(word_address, ram_.size()));
}

void Chip::ram_write(std::uint16_t word_address, std::uint16_t value) {
  bus_word_write(ram_select(word_address, ram_.size()), value);
}

// --- telegram processor's RAM port ----------------------------------------------------

void Chip::tp_run_beyond_the_ram() { throw std::out_of_range("tp_ram run beyond the RAM"); }

}  // namespace sercon::chip
