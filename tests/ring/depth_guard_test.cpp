// The depth guard (docs/serial-and-ring.md, "Depth guard"): in a ring where every node
// repeats, the master too, what circles is re-announced without end in the model. That is a
// sim::ModelLimit naming the cause, and it must come soon, not after minutes: the standard
// is "never a crash, hang or silent wrong answer". The case below is ring_fuzz's finding
// fuzz/findings/ring-all-repeat-guard-slow.bin written out (RING_FUZZ_TRACE=1 prints it), up
// to the write that lights the all-repeating ring. The receiver's plans walk its timeline
// at every change announced, so the way to the guard costs about the square of its limit:
// with 4096 changes this took 8 s (minutes under the fuzzer), with 1024 0.4 s
// (docs/fuzzing.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/ring/ring.hpp"
#include "sercon/sim/model_limit.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::ring {
namespace {

using chip::Chip;
using chip::ChipConfig;
using sim::Time;

constexpr Time kUs = sim::kMicrosecond;

// The finding's chips: SERCON816 at 32 MHz, SBAUD16 high, TM0 and TM1 high.
ChipConfig finding_config() {
  ChipConfig c;
  c.mclk_hz = 32'000'000;
  c.sbaud = false;
  c.sbaud16 = true;
  c.tm0 = true;
  c.tm1 = true;
  return c;
}

// A register write as ring_fuzz makes it: the register read back after it.
void write(Chip& c, std::uint16_t address, std::uint16_t value) {
  c.reg_write(address, value);
  c.reg_read(address);
}

void put(Chip& c, std::uint16_t at, std::initializer_list<std::uint16_t> words) {
  for (std::uint16_t w : words) c.ram_write(at++, w);
}

// ring_fuzz's bring-up, as a driver does it: master + slaves in CP4 at 2 Mbit/s, TSCYC
// 250 µs, an AT per slave and an MDT, slaves repeating.
void bring_up(Ring& ring, sim::Scheduler& s) {
  s.run_until(2'222'222);  // out of reset
  const std::size_t n = ring.slave_count() + 1;
  const auto slaves = static_cast<std::uint16_t>(n - 1);
  for (std::size_t i = 0; i < n; ++i) {
    Chip& c = ring.node(i);
    const bool master = i == 0;
    c.reg_write(0x01, master ? 0x0000 : 0x0008);  // SERMODE: REPON on the slaves
    c.reg_write(0x02, 0x0041);
    c.reg_write(0x0E, static_cast<std::uint16_t>(18 << 8 | 31));
    c.reg_write(0x0F, 250);
    c.reg_write(0x10, 250);
    c.reg_write(0x13, 1);
    put(c, 0, {0x7FC, 0x40});
    put(c, 0x7FC, {0xC000, 240});
    if (!master) {
      c.reg_write(0x15, 0xFFFC);
      c.reg_write(0x16, 6);
      const auto k = static_cast<std::uint16_t>(i);
      put(c, 0x40,
          {static_cast<std::uint16_t>(0x5000 | k), static_cast<std::uint16_t>(20 + 8 * (k - 1)), 3,
           0x48});
      put(c, 0x44, {0x8003, static_cast<std::uint16_t>(0x0100 | k), 0, 0});
      put(c, 0x48, {0x08FF, 0, static_cast<std::uint16_t>(3 * slaves), 0x52, 0});
      put(c, 0x4D, {0x8003, static_cast<std::uint16_t>(3 * (k - 1)), 0, 0, 0});
      put(c, 0x52, {0xC000, 240});
    } else {
      c.reg_write(0x0A, 4);
      std::uint16_t at = 0x40;
      for (std::uint16_t k = 1; k <= slaves; ++k, at += 10) {
        put(c, at,
            {static_cast<std::uint16_t>(0x0800 | k), 0, 3, static_cast<std::uint16_t>(at + 10), 0});
        put(c, static_cast<std::uint16_t>(at + 5), {0x8003, 0, 0, 0, 0});
      }
      const auto end = static_cast<std::uint16_t>(at + 4 + 4 * slaves);
      put(c, at,
          {0x50FF, static_cast<std::uint16_t>(20 + 8 * slaves + 12),
           static_cast<std::uint16_t>(3 * slaves), end});
      for (std::uint16_t k = 1; k <= slaves; ++k) {
        put(c, static_cast<std::uint16_t>(at + 4 + 4 * (k - 1)),
            {static_cast<std::uint16_t>((k == slaves ? 0x8000 : 0) | 3),
             static_cast<std::uint16_t>(0x0400 | k), 0, 0});
      }
      put(c, end, {0xC000, 240});
    }
    c.reg_write(0x03, 0x0100);  // ENTMT
  }
  ring.master().reg_write(0x01, static_cast<std::uint16_t>(ring.master().reg_read(0x01) | 0x0020));
}

TEST(DepthGuard, LightInARingWhereEveryNodeRepeatsEndsInTheGuardsError) {
  sim::Scheduler s;
  RingOptions options;
  options.fibre_lengths_m = {250.72, 1.59, 100.9, 0.15};
  Ring ring(s, finding_config(), std::vector<ChipConfig>(3, finding_config()), options);
  bring_up(ring, s);
  const auto step = [&](Time t) { s.run_until(s.now() + t); };
  step(5 * 250 * kUs);  // warm-up
  step(60'827);
  ring.serial(1).set_lazy_hops(false);
  ring.node(1).ram_write(0x73F, 0x1000);
  ring.node(0).ram_write(0x007, 0x8A6D);
  ring.fibre(2).set_bit_error_rate(0.1, 2560894732274382132ULL);
  put(ring.node(1), 0x47B, {0xC000, 0xFFFF});
  put(ring.master(), 0xC5,
      {0x0A7A, 0x000A, 0x0003, 0x00D2, 0x0000, 0x8003, 0x0000, 0x3A19, 0x6E10, 0xA43E, 0xC2DD,
       0x8D0C, 0x9ECB, 0x4801, 0x0096, 0x0008, 0x00DF, 0x8008, 0xFDBB, 0xAD16, 0x8E3D, 0x557B,
       0xAD54, 0x76FF, 0x3203, 0xB519, 0x0202, 0x000A, 0x0003, 0x00EC, 0x0000, 0x8403, 0x0000,
       0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0xC000, 0x00F0});
  ring.master().ram_write(1, 0xC5);  // COMPT1
  write(ring.master(), 0x01, 0x0000);
  write(ring.master(), 0x15, 0x0032);
  ring.fibre(1).restore_at(s.now() + 246'246'215);
  write(ring.master(), 0x14, 0x0002);
  ring.node(1).ram_write(0x008, 0xCF1D);
  step(167'336);
  ring.fibre(0).restore_at(s.now() + 78'406'746);
  step(72'087);
  ring.fibre(3).set_bit_error_rate(0.1, 16260872465180262404ULL);
  write(ring.master(), 0x01, 0x08DB);  // REPON on the master too (and SWRST)
  ring.switch_on_lines();              // the master's REPON off again
  ring.fibre(0).restore();
  ring.switch_on_lines();
  put(ring.node(1), 0x787, {0x1B03, 0x0014, 0x0000, 0x0777, 0x0000, 0x8000, 0x0002});
  ring.fibre(0).restore();
  ring.fibre(3).set_bit_error_rate(0.1, 15132094747964866560ULL);
  try {
    write(ring.master(), 0x01, 0xFFFF);  // REPON on every node, and the master lit
    s.run_until(s.now() + 2000 * kUs);
    FAIL() << "no error";
  } catch (const sim::ModelLimit& e) {
    EXPECT_NE(std::string(e.what()).find("every node repeats"), std::string::npos) << e.what();
    // The documented limit, which bounds how long the way there takes.
    EXPECT_NE(std::string(e.what()).find("1024 changes announced ahead"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sercon::ring
