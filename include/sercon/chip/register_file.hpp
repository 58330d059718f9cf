// The chip's 0x00..0x2A control registers: storage that obeys the access rules of the
// register map, plus hooks through which the chip's units act on writes and supply
// live values on reads (QEMU/VCML style: registers as data, behaviour in hooks).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "sercon/chip/register_map.hpp"
#include "sercon/chip/variant.hpp"

namespace sercon::chip {

class RegisterFile {
 public:
  // `written` is the raw bus value; `before` the stored value before the write.
  using WriteHook = std::function<void(std::uint16_t written, std::uint16_t before)>;
  // Gets the stored value, returns what the bus reads (e.g. a live counter).
  using ReadHook = std::function<std::uint16_t(std::uint16_t stored)>;

  explicit RegisterFile(Variant variant);

  Variant variant() const { return variant_; }

  // --- the µP's side (bus accesses) -------------------------------------------------
  // Unused bits read 0 (datasheet 4.1); addresses >= kRegisterCount read 0.
  std::uint16_t bus_read(std::uint8_t address) const;
  // RW bits are stored (except bits locked by lock()), W1C bits written 1 are cleared,
  // R bits and unused bits are ignored (datasheet 4.1); then the write hooks run.
  // Addresses >= kRegisterCount are ignored. `enabled` names the bits the access carries
  // (0x00FF / 0xFF00 for a byte write): other bits are untouched, and the hooks see them
  // as 0 in `written`, so a byte write never triggers an action bit of the other byte.
  void bus_write(std::uint8_t address, std::uint16_t value, std::uint16_t enabled = 0xFFFF);

  // --- the chip's side ----------------------------------------------------------------
  std::uint16_t value(std::uint8_t address) const { return values_.at(address); }
  bool bit(std::uint8_t address, std::uint16_t mask) const { return (value(address) & mask) != 0; }
  // Sets or clears bits whatever their access (status bits, latched interrupts, W1C).
  // Inline: most calls set a bit that is set already (an interrupt raised every cycle).
  void set_bits(std::uint8_t address, std::uint16_t mask, bool on) {
    put(address, mask, on ? mask : 0);
  }
  // Replaces the bits under `mask` with `bits`.
  void put(std::uint8_t address, std::uint16_t mask, std::uint16_t bits) {
    static_cast<void>(values_.at(address));  // the range check
    put_field(address, mask, bits);
  }
  // value(), put() and set_bits() without the range check, for an address known to be a
  // register's (a FieldRef's, resolved from the register table): units read and set fields
  // a few hundred times a cycle.
  std::uint16_t field_value(std::uint8_t address) const { return values_[address]; }
  void put_field(std::uint8_t address, std::uint16_t mask, std::uint16_t bits) {
    const std::uint16_t before = values_[address];
    const auto next = static_cast<std::uint16_t>((before & ~mask) | (bits & mask));
    if (next == before) return;
    values_[address] = next;
    changed(address);
  }
  void set_field_bits(std::uint8_t address, std::uint16_t mask, bool on) {
    put_field(address, mask, on ? mask : 0);
  }

  // RW bits under `mask` ignore bus writes while locked (delta spec 2.6.2: ENTMT and PHAS0
  // while INT_WDOG is set).
  void lock(std::uint8_t address, std::uint16_t mask, bool locked);
  // W1C bits under `mask` ignore a bus write of 1 while held: a latched interrupt whose
  // source is a level that is still high (INT_FIBBR while FIBBR, Interrupts::set_level).
  void hold(std::uint8_t address, std::uint16_t mask, bool held);

  void on_write(std::uint8_t address, WriteHook hook);
  void on_read(std::uint8_t address, ReadHook hook);
  // Any change of a value by the chip's side or the bus calls these (e.g. interrupt
  // outputs follow INTSTAT & IEN).
  void on_change(std::function<void(std::uint8_t address)> listener);
  // The same, called before every listener added with on_change() (these among themselves
  // in the order they were added): for a unit that keeps register fields as data, current
  // for whatever the other listeners run.
  void on_change_first(std::function<void(std::uint8_t address)> listener);

  // Table reset values for every register (pins and variant-specific bits: see Chip).
  void reset();
  // True while reset() loads them, one register after the other. A listener that drives a
  // pin from several registers or from its unit's state (INT0 from INTxPOL and INTSTAT,
  // DIV_CLK from POLDIVCLK and a pulse in progress) leaves the pin alone then: the unit's
  // reset (ChipUnit::reset) drives it once every register holds its reset value, so a pin
  // gets no zero-width pulse out of the half-reset registers.
  bool resetting() const { return resetting_; }

  const RegisterMasks& masks(std::uint8_t address) const { return masks_.at(address); }

 private:
  void changed(std::uint8_t address);

  Variant variant_;
  bool resetting_ = false;
  std::array<RegisterMasks, kRegisterCount> masks_{};
  std::array<std::uint16_t, kRegisterCount> values_{};
  std::array<std::uint16_t, kRegisterCount> locked_{};
  std::array<std::uint16_t, kRegisterCount> held_{};
  std::array<std::vector<WriteHook>, kRegisterCount> write_hooks_;
  std::array<ReadHook, kRegisterCount> read_hooks_;
  std::vector<std::function<void(std::uint8_t)>> change_listeners_;
  std::size_t first_listeners_ = 0;  // change_listeners_' first ones: on_change_first()
};

}  // namespace sercon::chip
