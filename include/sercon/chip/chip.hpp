// The SERCON816 / SERCON410B chip: register file, dual-port RAM, one sim::Signal per pin
// of datasheet Table 1, the µP bus interface, resets, and the functional units.
//
// How a unit plugs in (time base, watchdog, DIV_CLK, CON_CLK, interrupts, ...):
//  1. Derive from ChipUnit (chip_unit.hpp) and take `Chip&` in the constructor. There,
//     register RegisterFile hooks (chip.regs().on_write / on_read / on_change) and pin
//     watchers (chip.pin(Pin::CYC_CLK).watch(...)); keep the Chip& for later.
//  2. Add one line to Chip::build_units() in src/chip/chip_units.cpp:
//       add_unit<TimeBase>();
//     Units are built in that order, after the chip's own hooks, and are told about
//     resets in that order. Chip::unit<T>() finds a unit by type (e.g. the watchdog
//     asking the time base for its 1 µs tick).
//  3. reset(cause) is called at every reset after the registers hold their reset values;
//     release() when the chip leaves reset (see chip_unit.hpp). Do not schedule events
//     from the constructor: power-on is a reset + release like any other.
//  4. Drive output pins with set_output(pin, level), never pin(p).set(): set_output
//     remembers the level and keeps the pin high-impedance while OUTZ = 1.
//  5. Time: scheduler().now() in picoseconds; mclk() and next_mclk_edge() give the MCLK
//     grid (edge k at floor(k * 1e12 / f_MCLK) ps from time 0, exact for any frequency).
//  6. A unit's destructor cancels its pending events: a chip can be freed (C API) while
//     its scheduler runs on.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "sercon/chip/bus.hpp"
#include "sercon/chip/busy_arbiter.hpp"
#include "sercon/chip/chip_config.hpp"
#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/dpram.hpp"
#include "sercon/chip/mclk_divider.hpp"
#include "sercon/chip/pins.hpp"
#include "sercon/chip/register_file.hpp"
#include "sercon/chip/serial_clock.hpp"
#include "sercon/chip/test_mode.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/signal.hpp"

namespace sercon::chip {

class Chip {
 public:
  // Validates `config` (std::invalid_argument), sets the strap pins, builds the units and
  // runs the power-on reset.
  Chip(sim::Scheduler& scheduler, const ChipConfig& config);
  ~Chip();
  Chip(const Chip&) = delete;
  Chip& operator=(const Chip&) = delete;

  sim::Scheduler& scheduler() { return scheduler_; }
  const ChipConfig& config() const { return config_; }
  Variant variant() const { return config_.variant; }
  RegisterFile& regs() { return regs_; }
  const RegisterFile& regs() const { return regs_; }
  Dpram& ram() { return ram_; }
  const Dpram& ram() const { return ram_; }

  // --- µP bus ---------------------------------------------------------------------------
  // One bus cycle as the pins see it (bus.hpp). Throws std::invalid_argument when RAM
  // and registers are selected at once (a board fault: both would drive D15-0).
  BusResult bus(const BusCycle& cycle);
  // A write strobe through the pins (PinBus) in its two events. Its start asks the
  // BusyArbiter about the addressed RAM word and returns true when BUSYN goes low
  // (datasheet 3.5.7 t_MBSY: from the begin of the write access); its end writes D15-0
  // without asking again (t_MBHWH: BUSYN is high before the end). bus() does both at once.
  bool write_strobe_starts(const BusCycle& cycle);
  BusResult write_strobe_ends(const BusCycle& cycle);
  // Word accesses as the board's µP makes them with the present BUSWIDTH / BYTEDIR pins:
  // one 16-bit cycle, or two byte cycles (A0 = 0 first) on an 8-bit bus. The value is the
  // register's or RAM word's logical value. Registers: word_address 0x00..0x3F (0x2B..0x3F
  // read 0, writes ignored); RAM: word_address < ram().size(). std::out_of_range beyond.
  std::uint16_t reg_read(std::uint16_t word_address);
  void reg_write(std::uint16_t word_address, std::uint16_t value);
  std::uint16_t ram_read(std::uint16_t word_address);
  void ram_write(std::uint16_t word_address, std::uint16_t value);
  // The same word access with the chip selects and even byte address of `base` (board
  // decodings use it); `base.write`, `base.bhen` and `base.data` are ignored.
  std::uint16_t bus_word_read(const BusCycle& base);
  void bus_word_write(const BusCycle& base, std::uint16_t value);

  // --- the telegram processor's RAM port (internal side) ------------------------------
  // Records the word as in use during the present MCLK period (BUSYN for a µP access to
  // it in that period). `word` must be < ram().size().
  // Inline: the list walk makes hundreds of these per cycle.
  std::uint16_t tp_ram_read(std::uint16_t word) {
    const std::uint16_t value = ram_.read(word);  // throws std::out_of_range first
    busy_.internal_access(word);
    ++tp_ram_accesses_;
    return value;
  }
  void tp_ram_write(std::uint16_t word, std::uint16_t value) {
    ram_.write(word, value);
    busy_.internal_access(word);
    ++tp_ram_accesses_;
  }
  // A run of words from `first` (all < ram().size(), else std::out_of_range and nothing
  // done): the same as one tp_ram_read / tp_ram_write per word, in one go.
  void tp_ram_read_run(std::uint16_t first, std::span<std::uint16_t> out) {
    const std::span<const std::uint16_t> ram = ram_.contents();
    if (first + out.size() > ram.size()) tp_run_beyond_the_ram();
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = ram[first + i];
    busy_.internal_access_run(first, out.size());
    tp_ram_accesses_ += out.size();
  }
  void tp_ram_write_run(std::uint16_t first, std::span<const std::uint16_t> words) {
    if (first + words.size() > ram_.size()) tp_run_beyond_the_ram();
    for (std::size_t i = 0; i < words.size(); ++i) {
      ram_.write(static_cast<std::uint16_t>(first + i), words[i]);
    }
    busy_.internal_access_run(first, words.size());
    tp_ram_accesses_ += words.size();
  }
  // Words the telegram processor has read or written since the chip was built (a measure
  // of its work: statistics, and the fuzzer's work budget).
  std::uint64_t tp_ram_accesses() const {
    std::uint64_t n = tp_ram_accesses_;
    for (const TpRamPort* port : tp_ports_) n += port->accesses_;
    return n;
  }

  // The same port without the bounds checks, for a caller that checks every word itself
  // (TelegramRam: one check per access instead of one per layer): each word given must be
  // < size(). Reads, writes, BUSYN marks and the access count are those of tp_ram_read /
  // tp_ram_write. Valid as long as the chip. Neither copied nor moved: the port counts its
  // accesses itself (one add each, not through a pointer into the chip) and the chip adds
  // them up in tp_ram_accesses().
  class TpRamPort {
   public:
    TpRamPort(const TpRamPort&) = delete;
    TpRamPort& operator=(const TpRamPort&) = delete;
    ~TpRamPort() { std::erase(chip_->tp_ports_, this); }

    std::uint16_t size() const { return size_; }
    std::uint16_t read(std::uint16_t word) const {
      marks_.mark(word);
      ++accesses_;
      return words_[word];
    }
    void write(std::uint16_t word, std::uint16_t value) const {
      words_[word] = value;
      marks_.mark(word);
      ++accesses_;
    }
    void read_run(std::uint16_t first, std::span<std::uint16_t> out) const {
      const std::uint16_t* from = words_ + first;
      marks_.mark_run(first, out.size(), [&](std::size_t i) { out[i] = from[i]; });
      accesses_ += out.size();
    }
    void write_run(std::uint16_t first, std::span<const std::uint16_t> words) const {
      std::uint16_t* to = words_ + first;
      marks_.mark_run(first, words.size(), [&](std::size_t i) { to[i] = words[i]; });
      accesses_ += words.size();
    }
    // The words without a mark: for a caller that looks at a structure first and then
    // marks what it read as one run (touch_run).
    const std::uint16_t* words() const { return words_; }
    // The same for writing: a caller that writes words it has checked and marks them.
    std::uint16_t* words_to_write() const { return words_; }
    // Word `word` read and written back as change(value read) at one instant: the marks and
    // counts of read() and write() (the same word marked twice at one instant is marked once).
    template <typename Change>
    std::uint16_t update(std::uint16_t word, Change change) const {
      const std::uint16_t value = words_[word];
      words_[word] = change(value);
      marks_.mark(word);
      accesses_ += 2;
      return value;
    }
    // Word `word` read and written back as change(value read), and words first .. first +
    // count - 1 used (touch_run), at one instant: the marks and counts of the three.
    template <typename Change>
    std::uint16_t update_and_touch_run(std::uint16_t word, Change change, std::uint16_t first,
                                       std::size_t count) const {
      const std::uint16_t value = words_[word];
      words_[word] = change(value);
      marks_.mark_word_and_run(word, first, count);
      accesses_ += 2 + count;
      return value;
    }
    // Word `word` read and words first .. first + count - 1 used (touch_run), at one
    // instant: the marks and counts of the two.
    void read_and_touch_run(std::uint16_t word, std::uint16_t first, std::size_t count) const {
      marks_.mark_word_and_run(word, first, count);
      accesses_ += 1 + count;
    }
    // Words first .. first + count - 1 used now: marked and counted as read_run does.
    void touch_run(std::uint16_t first, std::size_t count) const {
      marks_.mark_run(first, count);
      accesses_ += count;
    }
    // write_run of `count` words given as little-endian byte pairs (a telegram's data as
    // it came off the line).
    void write_run_le(std::uint16_t first, const std::uint8_t* bytes, std::size_t count) const {
      static_assert(std::endian::native == std::endian::little);
      std::uint16_t* to = words_ + first;
      marks_.mark_run(first, count, [&](std::size_t i) { std::memcpy(to + i, bytes + 2 * i, 2); });
      accesses_ += count;
    }

   private:
    friend class Chip;
    explicit TpRamPort(Chip& chip)
        : words_(chip.ram_.unchecked_words()),
          marks_(chip.busy_.marks()),
          chip_(&chip),
          size_(chip.ram_.size()) {
      chip.tp_ports_.push_back(this);
    }

    std::uint16_t* words_;
    BusyArbiter::Marks marks_;
    Chip* chip_;
    std::uint16_t size_;
    mutable std::uint64_t accesses_ = 0;
  };
  // Built in place where it is kept (a prvalue: no copy).
  TpRamPort tp_ram_port() { return TpRamPort(*this); }

  // --- pins -----------------------------------------------------------------------------
  sim::Signal& pin(Pin p) { return pins_.at(index_of(p)); }
  const sim::Signal& pin(Pin p) const { return pins_.at(index_of(p)); }
  // The board drives an input (or a data/address line the chip is not driving).
  // std::invalid_argument for an output, a line the chip drives now, HighZ on a pin
  // without pull resistor, MCLK/SCLK (given as frequencies in ChipConfig), TEST = 1.
  void drive(Pin p, sim::Level level);
  // True while the chip drives `p` (outputs always; D15-0 / A15-0 when it drives them).
  bool drives(Pin p) const { return chip_drives_.at(index_of(p)); }
  // The level an input is read as: HighZ resolves through its pull resistor.
  bool input_high(Pin p) const;
  // A unit drives an output: while OUTZ = 1 the pin stays HighZ and takes `level` after.
  void set_output(Pin p, sim::Level level);
  void set_output(Pin p, bool high) { set_output(p, sim::level_of(high)); }

  // --- reset ----------------------------------------------------------------------------
  // SWRST (same as writing 0x0002 to register 0x01): reset, then run on at once.
  void software_reset();
  // RSTN = 0 or OUTZ = 1: registers held at reset values, register writes ignored.
  bool in_reset() const { return rstn_low_ || outz_; }
  bool outputs_off() const { return outz_; }  // OUTZ = 1
  ResetCause last_reset() const { return last_reset_; }

  // --- clocks and modes -----------------------------------------------------------------
  const MclkGrid& mclk() const { return mclk_; }
  // The longest gap between MCLK edges (1e12 / f_MCLK rounded up); the edges themselves
  // come from mclk() / next_mclk_edge().
  sim::Time mclk_period() const { return mclk_.period(); }
  sim::Time next_mclk_edge(sim::Time t) const;  // first MCLK rising edge at or after t
  // Bit rate (= TxC / RxC frequency) and SCLKO2 / SCLKO4 from pins and register 0x01.
  // All 0 while OUTZ = 1 (clocks off). The clock outputs are exposed as frequencies; their
  // Signals are not toggled (64 MHz edges would swamp the scheduler).
  SerialClocks serial_clocks() const;
  // Test generator for the serial unit: pins TM0/TM1 or TMODE2-0 (register 0x02 bits 9-11).
  TestMode test_mode() const;

  // --- units ----------------------------------------------------------------------------
  template <typename T>
  T* unit() {
    for (auto& u : units_) {
      if (auto* found = dynamic_cast<T*>(u.get())) return found;
    }
    return nullptr;
  }

 private:
  template <typename T>
  void add_unit() {
    static_assert(std::is_base_of_v<ChipUnit, T>);
    units_.push_back(std::make_unique<T>(*this));
  }
  void build_units();  // src/chip/chip_units.cpp: the list of units
  void watch_pins();
  void enter_reset(ResetCause cause);
  void leave_reset();
  void apply_pin_reset_bits();
  void refresh_pin_status_bits();
  void refresh_outputs();
  void on_sermode_write(std::uint16_t written);
  [[noreturn]] static void tp_run_beyond_the_ram();
  BusResult access(const BusCycle& cycle, bool ask_busy);
  BusResult take_access(const BusCycle& cycle, bool ask_busy);
  BusResult ram_cycle(const BusCycle& cycle, const ByteLanes& lanes, bool ask_busy);
  BusResult register_cycle(const BusCycle& cycle, const ByteLanes& lanes);

  sim::Scheduler& scheduler_;
  ChipConfig config_;
  MclkGrid mclk_;
  RegisterFile regs_;
  Dpram ram_;
  std::vector<sim::Signal> pins_;          // index == Pin; never resized
  std::vector<sim::Level> output_levels_;  // what each output drives when OUTZ = 0
  std::vector<bool> chip_drives_;          // InOut lines the chip drives now
  BusyArbiter busy_;
  std::uint64_t tp_ram_accesses_ = 0;       // tp_ram_read / tp_ram_write and their runs
  std::vector<const TpRamPort*> tp_ports_;  // each counts its own accesses
  bool rstn_low_ = false;
  bool outz_ = false;
  ResetCause last_reset_ = ResetCause::PowerOn;
  std::vector<std::unique_ptr<ChipUnit>> units_;
};

}  // namespace sercon::chip
