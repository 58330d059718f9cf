// One chip whose repeater passes RxD on to TxD1, for the lazy-hop tests at one node
// (docs/serial-and-ring.md, "Lazy hops"): lazy hops on or off, so a test can run the same
// scenario both ways and compare. And a ring where every node repeats, the master too
// ("Depth guard").
#pragma once

#include <cstdint>

#include "ring_bench.hpp"
#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/ring/ring.hpp"

namespace sercon::ring::testing {

inline constexpr sim::Time kBit16 = 62'500;  // one bit at 16 Mbit/s, in ps

inline void set_bits(chip::Chip& c, const chip::FieldRef& f, bool on) {
  const std::uint16_t v = c.reg_read(f.address);
  c.reg_write(f.address, static_cast<std::uint16_t>(on ? v | f.mask : v & ~f.mask));
}

// One chip at 16 Mbit/s with its repeater on and TxD1 driven (0x02 TXOE bit 0, TXLIGHT).
struct RepeatingChip {
  explicit RepeatingChip(bool lazy) : c(s, config_at_mbit(16)), u(*c.unit<chip::SerialUnit>()) {
    u.set_lazy_hops(lazy);
    set_bits(c, u.fields().repon, true);
    c.reg_write(0x02, 0x0041);
  }
  // TxD1 into `fibre`, whose far end is `far`.
  void repeat_into(Fibre& fibre, chip::LineListener& far) {
    fibre.connect(far);
    u.connect_txd(1, fibre.input());
  }
  // RxD idle after 1000 bit times, then `n` telegrams announced at once, `spacing` bit times
  // apart from `lead` bit times later; returns when the first begins.
  sim::Time idle_then_telegrams(int n, sim::Time spacing, sim::Time lead) {
    s.run_until(1000 * kBit16);
    u.rxd().line_condition(s.now(), chip::LineCondition::Idle, kBit16);
    s.run_until(s.now() + lead * kBit16);
    const sim::Time base = s.now() + 10 * kBit16;
    for (int i = 0; i < n; ++i) {
      u.rxd().line_burst(
          chip::LineBurst{base + i * spacing * kBit16, kBit16, telegram_bits(0x07, {0x55, 0x55})});
    }
    return base;
  }

  sim::Scheduler s;
  chip::Chip c;
  chip::SerialUnit& u;
};

// Master + `slaves` at 16 Mbit/s on 1 km fibres (a lap longer than short telegrams), lines
// on (Ring::switch_on_lines), then every repeater on, the master's too.
struct AllRepeatRing {
  explicit AllRepeatRing(std::size_t slaves, bool lazy = true)
      : ring(s, config_at_mbit(16), config_at_mbit(16), slaves, options(slaves)) {
    ring.switch_on_lines();
    for (std::size_t i = 0; i <= slaves; ++i) ring.serial(i).set_lazy_hops(lazy);
    set_bits(ring.master(), ring.serial(0).fields().repon, true);
  }
  static RingOptions options(std::size_t slaves) {
    RingOptions o;
    o.fibre_lengths_m.assign(slaves + 1, 1000.0);
    return o;
  }
  sim::Scheduler s;
  Ring ring;
};

}  // namespace sercon::ring::testing
