// Host code in pin callbacks on a running ring (sercon.h: "a pin callback may read and write
// registers, RAM and pins"; docs/timing.md §8: a callback hears a change when the step that
// made it is done). Seeded random hosts write registers and RAM and drive input pins from
// callbacks on every node's outputs while a CP4 ring runs: nothing they do may make the
// model throw, except the documented refusal of a ring where every node repeats
// (docs/serial-and-ring.md, "Ring": telegrams would circle it for ever). Two defects this
// found: an MST ending at a rate change (ReceivedTelegram::bit_period) and a callback
// running half-way through the chip's reaction to OUTZ (sim/signal.hpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "../chip/cp4_ring.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Pin kWatched[] = {Pin::INT0,    Pin::INT1,    Pin::IDLE,    Pin::RECACTN, Pin::CYC_CLK,
                            Pin::DIV_CLK, Pin::CON_CLK, Pin::TxD1,    Pin::TxD2,    Pin::L_ERRN,
                            Pin::WDOGN,   Pin::DMAREQR, Pin::DMAREQT, Pin::BUSYN};

sim::Level toggled(sim::Level level) {
  return level == sim::Level::High ? sim::Level::Low : sim::Level::High;
}

// One host action on `chip` (node `index`; 0 is the master), chosen by `rng`.
void act(std::mt19937_64& rng, Chip& chip, std::size_t index) {
  const auto value = static_cast<std::uint16_t>(rng());
  const auto read = [&chip](std::uint16_t reg) { return chip.reg_read(reg); };
  switch (rng() % 18) {
    case 0:
      chip.reg_write(kSerMode, static_cast<std::uint16_t>(read(kSerMode) | 0x0002));
      break;
    case 1:  // REPON, not the master's: a ring where every node repeats is refused
      if (index != 0) chip.reg_write(kSerMode, static_cast<std::uint16_t>(read(kSerMode) ^ kRepon));
      break;
    case 2:
      chip.reg_write(kTpCtrl, static_cast<std::uint16_t>(read(kTpCtrl) ^ kEntmt));
      break;
    case 3:
      chip.reg_write(kSerCtrl, static_cast<std::uint16_t>(read(kSerCtrl) ^ (value & 0x7F)));
      break;
    case 4:
      chip.reg_write(kPhase, value & 0xFF);
      break;
    case 5:
      chip.ram_write(static_cast<std::uint16_t>(value % 2048), static_cast<std::uint16_t>(rng()));
      break;
    case 6:
      chip.reg_write(kSerMode, static_cast<std::uint16_t>(read(kSerMode) ^ (kEntsbaud | kSwbaud)));
      break;
    case 7:
      chip.reg_write(static_cast<std::uint16_t>(value % 0x2B), static_cast<std::uint16_t>(rng()));
      break;
    case 8:
      chip.reg_write(kIntStat, 0xFFFF);
      break;
    case 9:
      chip.reg_write(kClockDiv, value);
      break;
    case 10:
      chip.reg_write(kPhase, static_cast<std::uint16_t>(value % 5));
      break;
    case 11:
      chip.reg_write(kTcycstart, static_cast<std::uint16_t>(value % 300));
      break;
    case 12:
      chip.ram_write(static_cast<std::uint16_t>(kList + value % 64),
                     static_cast<std::uint16_t>(rng()));
      break;
    case 13:
      chip.reg_write(kSerMode, static_cast<std::uint16_t>(read(kSerMode) ^ kRegmode));
      break;
    case 14:
      chip.drive(Pin::RSTN, toggled(chip.pin(Pin::RSTN).level()));
      break;
    case 15:
      chip.drive(Pin::SBAUD, toggled(chip.pin(Pin::SBAUD).level()));
      break;
    case 16:
      chip.drive(Pin::OUTZ, chip.pin(Pin::OUTZ).level() == sim::Level::High ? sim::Level::Low
                                                                            : sim::Level::High);
      break;
    default:
      chip.drive(Pin::CYC_CLK, toggled(chip.pin(Pin::CYC_CLK).level()));
      break;
  }
}

// Runs 60 cycles of a master + 3 slaves with seeded callbacks (at most 40 actions, counted
// in `actions`); returns the master's DPRAM, or throws what the model threw.
std::vector<std::uint16_t> run_seed(std::uint64_t seed, int& actions) {
  std::mt19937_64 rng(seed);
  Cp4Ring r(layout_for(3, 250));
  ring::Ring& ring = r.ring();
  const std::size_t nodes = ring.slave_count() + 1;
  int budget = 40;
  for (std::size_t i = 0; i < nodes; ++i) {
    Chip& chip = ring.node(i);
    chip.reg_write(kIen0A, 0x3FFF);
    chip.reg_write(kIen1A, 0x3FFF);
    for (const Pin p : kWatched) {
      if (rng() % 3 != 0) continue;
      chip.pin(p).watch([&, nodes](sim::Level) {
        if (budget <= 0 || rng() % 4 != 0) return;
        --budget;
        ++actions;
        const std::size_t target = rng() % nodes;
        act(rng, ring.node(target), target);
      });
    }
  }
  r.run_cycles(60);
  std::vector<std::uint16_t> ram;
  for (std::uint16_t w = 0; w < 2048; ++w) ram.push_back(ring.master().ram_read(w));
  return ram;
}

bool circles(const std::exception& e) {
  return std::string(e.what()).find("telegrams circle a ring") != std::string::npos;
}

TEST(CallbackReentry, HostActionsFromPinCallbacksNeverBreakTheModel) {
  int actions = 0;
  for (std::uint64_t seed = 0; seed < 600; ++seed) {
    try {
      run_seed(seed, actions);
    } catch (const std::exception& e) {
      if (!circles(e)) ADD_FAILURE() << "seed " << seed << ": " << e.what();
    }
  }
  EXPECT_GT(actions, 600 * 10);  // the callbacks did act
}

// Determinism: the same seed, the same callbacks, the same ring.
TEST(CallbackReentry, TheSameSeedGivesTheSameRing) {
  int actions = 0;
  EXPECT_EQ(run_seed(7, actions), run_seed(7, actions));
  EXPECT_GT(actions, 0);
}

}  // namespace
}  // namespace sercon::chip
