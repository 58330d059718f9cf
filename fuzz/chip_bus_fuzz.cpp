// libFuzzer target: random bus cycles (word API, raw cycles, pin-level strobes), pin
// changes, telegram-processor RAM accesses and time steps against one chip. Besides
// crashes and sanitizer reports it checks invariants the specification states:
// unused register bits read 0 (datasheet 4.1), VERSION (delta spec 2.11.1.1), OUTZ floats
// every output but NDTRO (Table 1), BUSYN low for at most one MCLK (delta spec 2.8), and
// the RAM keeps what the µP wrote.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/register_map.hpp"
#include "sercon/sim/scheduler.hpp"

namespace {

using sercon::chip::BusCycle;
using sercon::chip::Chip;
using sercon::chip::ChipConfig;
using sercon::chip::Pin;
using sercon::sim::Level;
using sercon::sim::Time;

[[noreturn]] void violated(const char* what) {
  std::fprintf(stderr, "invariant violated: %s\n", what);
  std::abort();
}

void check(bool ok, const char* what) {
  if (!ok) violated(what);
}

ChipConfig fuzzed_config(FuzzedDataProvider& in) {
  static constexpr std::int64_t kMclk[] = {12'500'000, 16'000'000, 20'000'000, 25'000'000,
                                           32'000'000, 40'000'000, 50'000'000, 64'000'000};
  ChipConfig c;
  c.variant =
      in.ConsumeBool() ? sercon::chip::Variant::Sercon816 : sercon::chip::Variant::Sercon410B;
  c.mclk_hz = kMclk[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kMclk) - 1)];
  c.sbaud = in.ConsumeBool();
  c.sbaud16 = c.variant == sercon::chip::Variant::Sercon410B || in.ConsumeBool();
  c.tm0 = in.ConsumeBool();
  c.tm1 = in.ConsumeBool();
  c.buswidth = in.ConsumeBool();
  c.bytedir = in.ConsumeBool();
  return c;
}

// Values that make registers act: SWRST, the watchdog trigger, all ones, small times.
std::uint16_t fuzzed_value(FuzzedDataProvider& in) {
  static constexpr std::uint16_t kInteresting[] = {0x0000, 0x0001, 0x0002, 0x0042, 0x00FF, 0x0100,
                                                   0x0400, 0x8000, 0xFFFF, 31,     1000};
  if (in.ConsumeBool()) {
    return kInteresting[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kInteresting) - 1)];
  }
  return in.ConsumeIntegral<std::uint16_t>();
}

void check_register_read(Chip& chip, std::uint16_t address, std::uint16_t value) {
  if (chip.outputs_off()) {
    check(value == 0xFFFF, "a read under OUTZ floats to 0xFFFF");
    return;
  }
  if (address >= sercon::chip::kRegisterCount) {
    check(value == 0, "registers 0x2B..0x3F read 0");
    return;
  }
  const auto masks =
      sercon::chip::register_masks(static_cast<std::uint8_t>(address), chip.variant());
  check((value & ~masks.readable) == 0, "unused register bits read 0");
  if (address == 0) check(value == sercon::chip::version_of(chip.variant()), "VERSION");
}

void check_outputs(Chip& chip) {
  if (!chip.outputs_off()) return;
  for (std::size_t i = 0; i < sercon::chip::kPinCount; ++i) {
    const Pin p = sercon::chip::pin_at(i);
    if (sercon::chip::pin_info(p).direction != sercon::chip::PinDirection::Out) continue;
    const bool floating = chip.pin(p).level() == Level::HighZ;
    check(p == Pin::NDTRO ? !floating : floating, "OUTZ floats every output but NDTRO");
  }
}

// Watches BUSYN: every low pulse lasts at most one MCLK period.
struct BusyWatch {
  explicit BusyWatch(Chip& chip) : chip_(chip) {
    chip.pin(Pin::BUSYN).watch([this](Level level) {
      const Time now = chip_.scheduler().now();
      if (level == Level::Low) {
        low_since_ = now;
      } else if (low_since_ >= 0) {
        check(now - low_since_ <= chip_.mclk_period(), "BUSYN low for at most one MCLK");
        low_since_ = -1;
      }
    });
  }
  void check_now() const {
    if (low_since_ >= 0) {
      check(chip_.scheduler().now() - low_since_ <= chip_.mclk_period(),
            "BUSYN low for at most one MCLK");
    }
  }
  Chip& chip_;
  Time low_since_ = -1;
};

// Work per input is bounded by events and by the telegram processor's RAM accesses, not
// by simulated time: a chip programmed for a cycle every few MCLK periods makes millions
// of events in a few simulated milliseconds, and each cycle may walk a list of a thousand
// headers.
struct WorkBudget {
  std::size_t events_left = 100'000;
  std::uint64_t tp_access_limit = 1'000'000;
  // Runs events up to `until`; false (the clock left where it is) when the budget ran out.
  bool run_until(Chip& chip, Time until) {
    sercon::sim::Scheduler& scheduler = chip.scheduler();
    for (;;) {
      const auto next = scheduler.next_time();
      if (!next || *next > until) {
        scheduler.run_until(until);
        return true;
      }
      if (events_left == 0 || chip.tp_ram_accesses() > tp_access_limit) return false;
      --events_left;
      scheduler.step();
    }
  }
};

void drive(Chip& chip, Pin p, Level level) {
  try {
    chip.drive(p, level);
  } catch (const std::invalid_argument&) {
    // Refused on purpose: an output, a clock, TEST high, a line the chip drives.
  }
}

// Returns false when the input's work budget is spent.
bool one_operation(FuzzedDataProvider& in, Chip& chip, BusyWatch& busy, WorkBudget& budget) {
  sercon::sim::Scheduler& scheduler = chip.scheduler();
  const std::uint16_t ram_words = chip.ram().size();
  switch (in.ConsumeIntegralInRange(0, 8)) {
    case 0: {  // register word access
      const auto address = in.ConsumeIntegralInRange<std::uint16_t>(0, 0x3F);
      if (in.ConsumeBool()) chip.reg_write(address, fuzzed_value(in));
      check_register_read(chip, address, chip.reg_read(address));
      break;
    }
    case 1: {  // RAM word access: what is written reads back
      const auto address = in.ConsumeIntegralInRange<std::uint16_t>(0, ram_words - 1);
      const std::uint16_t value = in.ConsumeIntegral<std::uint16_t>();
      chip.ram_write(address, value);
      const std::uint16_t read = chip.ram_read(address);
      check(chip.outputs_off() ? read == 0xFFFF : read == value, "RAM keeps what was written");
      break;
    }
    case 2: {  // raw bus cycle with any chip selects and byte lanes
      BusCycle c;
      c.write = in.ConsumeBool();
      c.address = in.ConsumeIntegral<std::uint16_t>();
      c.data = fuzzed_value(in);
      c.bhen = in.ConsumeBool();
      c.mcsn0 = in.ConsumeBool();
      c.mcsn1 = in.ConsumeBool();
      c.pcsn0 = in.ConsumeBool();
      c.pcs1 = in.ConsumeBool();
      try {
        const auto r = chip.bus(c);
        check((r.data | r.driven) == 0xFFFF || c.write, "undriven data lines read 1");
      } catch (const std::invalid_argument&) {
        check(sercon::chip::decode_target(c) == sercon::chip::BusTarget::Both,
              "only a double select is refused");
      }
      break;
    }
    case 3: {  // the telegram processor's port
      const auto address = in.ConsumeIntegralInRange<std::uint16_t>(0, ram_words - 1);
      if (in.ConsumeBool()) {
        chip.tp_ram_write(address, in.ConsumeIntegral<std::uint16_t>());
      } else {
        chip.tp_ram_read(address);
      }
      break;
    }
    case 4: {  // any pin, any level
      const auto p = sercon::chip::pin_at(
          in.ConsumeIntegralInRange<std::size_t>(0, sercon::chip::kPinCount - 1));
      drive(chip, p, static_cast<Level>(in.ConsumeIntegralInRange(0, 2)));
      break;
    }
    case 5: {  // a pin-level read or write strobe on the current pins
      const Pin strobe = in.ConsumeBool() ? Pin::RDN : Pin::WRN;
      drive(chip, strobe, Level::Low);
      const Time hold = in.ConsumeBool() ? in.ConsumeIntegralInRange<Time>(0, 200'000) : 0;
      if (!budget.run_until(chip, scheduler.now() + hold)) return false;
      drive(chip, strobe, Level::High);
      break;
    }
    case 6: {  // a short time step (up to 20 µs)
      const Time step = in.ConsumeIntegralInRange<Time>(0, 20'000'000);
      if (!budget.run_until(chip, scheduler.now() + step)) return false;
      break;
    }
    case 7: {  // a long time step (up to 5 ms): lets timers and the watchdog run out
      const Time step = in.ConsumeIntegralInRange<Time>(0, 5'000'000'000);
      if (!budget.run_until(chip, scheduler.now() + step)) return false;
      break;
    }
    case 8: {  // MCLK-aligned step, so collisions land on period edges
      if (!budget.run_until(chip, chip.next_mclk_edge(scheduler.now() + 1))) return false;
      break;
    }
  }
  busy.check_now();
  check_outputs(chip);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  sercon::sim::Scheduler scheduler;
  Chip chip(scheduler, fuzzed_config(in));
  BusyWatch busy(chip);
  WorkBudget budget;
  for (int ops = 0; ops < 256 && in.remaining_bytes() > 0; ++ops) {
    if (!one_operation(in, chip, busy, budget)) break;
  }
  return 0;
}
