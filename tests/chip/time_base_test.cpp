// The µs time base and the cycle counter TCNT (docs/timing.md, "The cycle counter TCNT"):
// MCLKDIV makes the tick, TCNTST / MCLKST load the counter at MST detection, and with the
// driver formulas of facts §5 the counter steps from c to c + 1 c µs after the end of the
// MST.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

ChipConfig config_mhz(std::int64_t mhz) {
  ChipConfig c;
  c.mclk_hz = mhz * 1'000'000;
  return c;
}

// Delta spec 2.11.1.2 / facts §5: "a driver writes (MCLKST << 8) | (f_MCLK in MHz - 1):
// MCLKDIV makes the 1 µs time base". After reset the counter runs on that tick.
TEST(TimeBase, MclkdivMakesTheMicrosecondTick) {
  TimingBench b(config_mhz(32));
  const Time t = b.mclk();
  b.chip.reg_write(kClockDiv, 31);
  // The divider reloads MCLKDIV at its next tick (edge 1, still MCLKDIV = 0 from reset),
  // then ticks every 32 MCLK periods: edges 1, 33, 65, ...
  for (std::int64_t k = 0; k < 50; ++k) {
    const Time tick = (1 + 32 * k) * t;
    EXPECT_EQ(b.read_at(tick - 1, kTcnt), k) << k;
    EXPECT_EQ(b.read_at(tick, kTcnt), k + 1) << k;
  }
  EXPECT_EQ(b.time_base().tick_duration(), kMicrosecond);
}

// Delta spec 2.11.1.2: the 410B's MCLKDIV is 0EH.4-0 and MCLKST 0EH.12-8. Written 63 and
// 33, they are 31 and 1 there: a 32-period tick, and a first tick 1 period after a load.
TEST(TimeBase, The410BHasFiveBitDividers) {
  ChipConfig config = config_410b();
  config.mclk_hz = 32'000'000;
  TimingBench b(config);
  const Time t = b.mclk();
  b.chip.reg_write(kClockDiv, 33 << 8 | 63);
  EXPECT_EQ(b.time_base().tick_period(), 32);
  b.chip.reg_write(kTcntst, 7);
  b.run_to(10 * kMicrosecond);
  b.cycles().mst_detected(b.now());
  const Time first = 10 * kMicrosecond + 3 * t + 1 * t;
  EXPECT_EQ(b.read_at(first - 1, kTcnt), 7);
  EXPECT_EQ(b.read_at(first, kTcnt), 8);
  EXPECT_EQ(b.read_at(first + 32 * t, kTcnt), 9);
}

// Datasheet 4.1 / register table: TCNT is a status register, writes are ignored.
TEST(TimeBase, TcntIsReadOnly) {
  TimingBench b;
  b.chip.reg_write(kClockDiv, b.us_divider());
  b.run_to(10 * kMicrosecond);
  const std::uint16_t before = b.chip.reg_read(kTcnt);
  b.chip.reg_write(kTcnt, 0x1234);
  EXPECT_EQ(b.chip.reg_read(kTcnt), before);
}

// A 16-bit register: the counter wraps modulo 2^16.
TEST(TimeBase, TcntWrapsAt16Bits) {
  TimingBench b(config_mhz(32));
  b.chip.reg_write(kClockDiv, 31);
  const Time t = b.mclk();
  const Time tick_65536 = (1 + 32 * 65535) * t;  // the 65536th tick
  EXPECT_EQ(b.read_at(tick_65536 - 1, kTcnt), 0xFFFF);
  EXPECT_EQ(b.read_at(tick_65536, kTcnt), 0);
  EXPECT_EQ(b.read_at(tick_65536 + 32 * t, kTcnt), 1);
}

// Decision (docs/timing.md): MCLKDIV is reloaded at each tick, so a new value takes effect
// after the tick that is pending when it is written.
TEST(TimeBase, NewMclkdivCountsFromTheNextTick) {
  TimingBench b(config_mhz(32));
  const Time t = b.mclk();
  b.chip.reg_write(kClockDiv, 31);     // ticks at edges 1 + 32k
  b.write_at(100 * t, kClockDiv, 15);  // pending tick: edge 129; then every 16
  EXPECT_EQ(b.read_at(129 * t - 1, kTcnt), 4);
  EXPECT_EQ(b.read_at(129 * t, kTcnt), 5);
  EXPECT_EQ(b.read_at(145 * t - 1, kTcnt), 5);
  EXPECT_EQ(b.read_at(145 * t, kTcnt), 6);
  EXPECT_EQ(b.time_base().tick_duration(), 16 * t);
}

// Bad input (docs/timing.md): MCLKDIV = 0 gives a tick of one MCLK period, not 1 µs. The
// counter then simply counts MCLK periods.
TEST(TimeBase, MclkdivZeroTicksEveryMclkPeriod) {
  TimingBench b;
  const Time t = b.mclk();
  EXPECT_EQ(b.read_at(10 * t - 1, kTcnt), 9);
  EXPECT_EQ(b.read_at(10 * t, kTcnt), 10);
}

// Table 1 RSTN: "Reset, active low". Held in reset, the counter is stopped at 0; it
// restarts from 0 when the chip leaves reset.
TEST(TimeBase, CounterHeldAtZeroInReset) {
  TimingBench b(config_mhz(32));
  b.chip.reg_write(kClockDiv, 31);
  b.run_to(50 * kMicrosecond);
  EXPECT_GT(b.chip.reg_read(kTcnt), 40);
  b.chip.drive(Pin::RSTN, Level::Low);
  EXPECT_EQ(b.read_at(60 * kMicrosecond, kTcnt), 0);
  b.chip.drive(Pin::RSTN, Level::High);  // MCLKDIV is 0 again after reset
  EXPECT_EQ(b.read_at(60 * kMicrosecond + 5 * b.mclk(), kTcnt), 5);
}

// --- the driver formulas, end to end ---------------------------------------------------

struct DriverTiming {
  std::int64_t tcntst;
  std::int64_t mclkst;
  bool half_period_offset;  // (TCNTST - t_start) * f_MCLK = n + 1/2
};

// Facts §5: t_start = 5.5 t_bit + 3.5 / f_MCLK; TCNTST = floor(t_start + 1);
// MCLKST = int((TCNTST - t_start) * f_MCLK + 1). Evaluated exactly, in half picoseconds.
DriverTiming driver_timing(Time bit_ps, Time mclk_ps) {
  const std::int64_t t_start_half_ps = 11 * bit_ps + 7 * mclk_ps;
  const std::int64_t us_half_ps = 2 * kMicrosecond;
  DriverTiming d{};
  d.tcntst = (t_start_half_ps + us_half_ps) / us_half_ps;
  const std::int64_t rest_half_ps = d.tcntst * us_half_ps - t_start_half_ps;  // x * 2 T
  d.mclkst = (rest_half_ps + 2 * mclk_ps) / (2 * mclk_ps);
  d.half_period_offset = rest_half_ps % (2 * mclk_ps) == mclk_ps;
  return d;
}

struct FormulaCase {
  std::int64_t mbit;
  std::int64_t mclk_mhz;
};

class DriverFormula : public ::testing::TestWithParam<FormulaCase> {};

// Facts §5: "the chip keeps a µs cycle counter that it loads with TCNTST when it detects
// an MST, which compensates the 5.5-bit detection delay; telegram header times are µs
// offsets in that cycle". The MST is recognised 5.5 bit times after its end; the chip
// synchronises that to MCLK (3..4 periods, the 3.5 / f_MCLK of t_start). Then the counter
// must step from c to c + 1 at c µs after the MST's end: at the first MCLK edge at or
// after it when (TCNTST - t_start) * f_MCLK ends in .5 (the formula's design case), and
// within -1/2 .. +3/2 MCLK periods of it always. Checked by reading TCNT over the bus
// just before and at each step, for MST ends at several phases of MCLK.
TEST_P(DriverFormula, CounterValueCMeansCMicrosecondsAfterTheMstEnd) {
  const FormulaCase fc = GetParam();
  const Time bit = kMicrosecond / fc.mbit;
  for (const Time phase : {Time{0}, Time{1}, Time{4321}, Time{7777}, Time{15000}}) {
    TimingBench b(config_mhz(fc.mclk_mhz));
    const Time t = b.mclk();
    const DriverTiming d = driver_timing(bit, t);
    ASSERT_LE(d.mclkst, 63) << "MCLKST must fit its 6 bits";
    b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>((d.mclkst << 8) | (fc.mclk_mhz - 1)));
    b.chip.reg_write(kTcntst, static_cast<std::uint16_t>(d.tcntst));

    const Time mst_end = 20 * kMicrosecond + phase % t;
    const Time recognised = mst_end + 11 * bit / 2;
    b.run_to(recognised);
    b.cycles().mst_detected(recognised);
    const Time loaded = edge_at_or_after(recognised, t) + 3 * t;
    EXPECT_EQ(b.read_at(loaded, kTcnt), d.tcntst);

    Time previous_step = 0;
    for (std::int64_t c = d.tcntst; c < d.tcntst + 40; ++c) {
      const std::string where = std::to_string(fc.mbit) + " Mbit/s, " +
                                std::to_string(fc.mclk_mhz) + " MHz, phase " +
                                std::to_string(phase) + ", c = " + std::to_string(c);
      const Time boundary = mst_end + c * kMicrosecond;
      const Time from = boundary - t / 2;
      const Time to = boundary + 3 * t / 2;
      ASSERT_EQ(b.read_at(std::max(from - 1, b.now()), kTcnt), c) << where;
      Time step = 0;
      for (Time e = edge_at_or_after(from, t); e < to; e += t) {
        if (b.read_at(e, kTcnt) == c + 1) {
          step = e;
          break;
        }
        ASSERT_EQ(b.chip.reg_read(kTcnt), c) << where;
      }
      ASSERT_NE(step, 0) << "no step within -T/2..+3T/2 of the boundary: " << where;
      if (d.half_period_offset) {
        EXPECT_EQ(step, edge_at_or_after(boundary, t)) << where;
      }
      if (previous_step != 0) {
        EXPECT_EQ(step - previous_step, kMicrosecond) << where;
      }
      previous_step = step;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    BitRatesAndMclk, DriverFormula,
    ::testing::Values(FormulaCase{2, 16}, FormulaCase{2, 20}, FormulaCase{2, 25},
                      FormulaCase{2, 32}, FormulaCase{2, 50}, FormulaCase{2, 64},
                      FormulaCase{4, 16}, FormulaCase{4, 25}, FormulaCase{4, 32},
                      FormulaCase{4, 40}, FormulaCase{4, 64}, FormulaCase{8, 16},
                      FormulaCase{8, 20}, FormulaCase{8, 32}, FormulaCase{8, 50},
                      FormulaCase{8, 64}, FormulaCase{16, 16}, FormulaCase{16, 25},
                      FormulaCase{16, 32}, FormulaCase{16, 40}, FormulaCase{16, 64}),
    [](const ::testing::TestParamInfo<FormulaCase>& param_info) {
      return std::to_string(param_info.param.mbit) + "Mbit_" +
             std::to_string(param_info.param.mclk_mhz) + "MHz";
    });

// The design case of the formula: at 2 Mbit/s and 32 MHz t_start = 2.859375 µs, so
// TCNTST = 3 and MCLKST = int(4.5 + 1) = 5 (worked by hand).
TEST(DriverFormulaByHand, TwoMbitThirtyTwoMegahertz) {
  const DriverTiming d = driver_timing(500'000, 31'250);
  EXPECT_EQ(d.tcntst, 3);
  EXPECT_EQ(d.mclkst, 5);
  EXPECT_TRUE(d.half_period_offset);
}

// Decision (docs/timing.md): the first tick after a load comes MCLKST MCLK periods later,
// MCLKST = 0 counting as 1; values above MCLKDIV + 1 lengthen the first µs (the formula
// gives MCLKDIV + 2 when t_start is a whole number of µs).
TEST(TimeBase, FirstTickComesMclkstPeriodsAfterTheLoad) {
  for (const std::int64_t mclkst : {0, 1, 5, 31, 33, 63}) {
    TimingBench b(config_mhz(32));
    const Time t = b.mclk();
    b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>(mclkst << 8 | 31));
    b.chip.reg_write(kTcntst, 7);
    const Time recognised = 10 * kMicrosecond;
    b.run_to(recognised);
    b.cycles().mst_detected(recognised);
    const Time loaded = recognised + 3 * t;  // 10 µs is an MCLK edge
    const Time first = loaded + (mclkst == 0 ? 1 : mclkst) * t;
    EXPECT_EQ(b.read_at(first - 1, kTcnt), 7) << mclkst;
    EXPECT_EQ(b.read_at(first, kTcnt), 8) << mclkst;
    EXPECT_EQ(b.read_at(first + 32 * t - 1, kTcnt), 8) << mclkst;
    EXPECT_EQ(b.read_at(first + 32 * t, kTcnt), 9) << mclkst;
  }
}

// Cycle-time events (used by DIV_CLK, CON_CLK, the windows, later the telegram headers):
// exactly at the step out of the given cycle time, in picoseconds; dropped by the next
// cycle start; none for a step already behind.
TEST(TimeBase, CycleTimeEventsRunAtTheStep) {
  TimingBench b(config_mhz(25));
  const Time t = b.mclk();
  b.chip.reg_write(kClockDiv, 3 << 8 | 24);
  b.chip.reg_write(kTcntst, 2);
  b.run_to(5 * kMicrosecond);
  b.cycles().mst_detected(b.now());
  const Time loaded = 5 * kMicrosecond + 3 * t;
  b.run_to(loaded);
  std::vector<Time> ran;
  auto& tb = b.time_base();
  EXPECT_EQ(tb.at_cycle_time(1, [&] { ran.push_back(b.now()); }),
            TimeBase::CycleEvent{});  // before TCNTST
  tb.at_cycle_time(2, [&] { ran.push_back(b.now()); });
  tb.at_cycle_time(100, [&] { ran.push_back(b.now()); });
  const auto dropped = tb.at_cycle_time(400, [&] { ran.push_back(b.now()); });
  EXPECT_EQ(tb.when(dropped), loaded + (3 + 398 * 25) * t);
  b.run_to(300 * kMicrosecond);
  b.cycles().mst_detected(b.now());  // a new cycle before cycle time 400
  b.run_to(1000 * kMicrosecond);
  ASSERT_EQ(ran.size(), 2u);
  EXPECT_EQ(ran[0], loaded + 3 * t);
  EXPECT_EQ(ran[1], loaded + (3 + 98 * 25) * t);
}

// TimeBase::defer_after_restart (a slave's window close at every MST) skips step_ahead()'s
// tests: right after a cycle start's divider restart it gives the event the time the general
// path gives, for every step from TCNTST on, MCLKST, MCLKDIV, on whole- and part-picosecond
// grids, at and between MCLK edges.
TEST(TimeBase, DeferAfterRestartIsTheGeneralStep) {
  for (const std::int64_t mhz : {25, 30}) {
    for (const std::int64_t mclkst : {0, 1, 5}) {
      for (const std::int64_t divider : {0, 7, 24}) {
        for (const std::int64_t tcntst : {0, 3, 40}) {
          TimingBench b(config_mhz(mhz));
          auto& tb = b.time_base();
          b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>(mclkst << 8 | divider));
          b.chip.reg_write(kTcntst, static_cast<std::uint16_t>(tcntst));
          TimeBase::OwnedEvent owned(tb, nullptr);
          for (const Time at : {5 * kMicrosecond, 7 * kMicrosecond + 11}) {
            b.run_to(at);
            for (const std::int64_t step : {0, 1, 2, 500}) {
              const std::int64_t cycle_time = tcntst + step;
              std::optional<Time> general;
              tb.start_cycle(CycleKind::Master, [&](const CycleStart&) {
                general = tb.time_of_cycle_time(cycle_time);
                tb.defer_after_restart(owned, cycle_time, [](void*) {});
              });
              ASSERT_TRUE(general.has_value());
              EXPECT_EQ(owned.when(), *general) << mhz << " " << mclkst << " " << divider << " "
                                                << tcntst << " " << at << " " << step;
              EXPECT_TRUE(owned.pending());
              owned.cancel();
            }
          }
        }
      }
    }
  }
}

// docs/timing.md, "Cycle-time events": a cycle-time event exists exactly for the steps the counter
// has not made yet. The time base decides "ahead" from the step's edge time alone (not by
// counting ticks): at every MCLK edge and just before it, around a restart, on a grid
// whose period is not whole picoseconds (30 MHz) and after MCLKDIV changes, a step out of
// c is ahead iff the counter is at most c, and the counter makes it exactly then.
TEST(TimeBase, AStepIsAheadExactlyWhileTheCounterHasNotMadeIt) {
  for (const std::int64_t mhz : {25, 30}) {
    TimingBench b(config_mhz(mhz));
    const Time t = b.mclk();
    const auto divider = static_cast<std::uint16_t>(mhz - 1);
    b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>(5 << 8 | divider));
    b.chip.reg_write(kTcntst, 3);
    auto& tb = b.time_base();
    const auto check_until = [&](Time until) {
      for (Time edge = b.now() / t; edge * t <= until; edge += 7) {
        for (const Time at : {edge * t - 1, edge * t, edge * t + 1}) {
          if (at < b.now()) continue;
          b.run_to(at);
          const std::int64_t count = tb.count();
          for (std::int64_t c = count - 2; c <= count + 2; ++c) {
            const auto step = tb.time_of_cycle_time(c);
            ASSERT_EQ(step.has_value(), c >= count) << mhz << " MHz, " << at << " ps, c " << c;
            if (step) {
              ASSERT_GT(*step, at) << mhz << " MHz, " << at << " ps, c " << c;
            }
          }
          const auto next = tb.time_of_cycle_time(count);
          ASSERT_TRUE(next.has_value());
        }
      }
    };
    b.run_to(4 * kMicrosecond);
    b.cycles().mst_detected(b.now());
    check_until(12 * kMicrosecond);
    b.write_at(12 * kMicrosecond + t / 2, kClockDiv, static_cast<std::uint16_t>(divider / 3));
    check_until(20 * kMicrosecond);
    b.write_at(20 * kMicrosecond + t / 3, kClockDiv, static_cast<std::uint16_t>(divider * 2));
    check_until(40 * kMicrosecond);
    // The counter steps out of c at the time given for c, not an edge earlier or later.
    const std::int64_t count = tb.count();
    const Time step = *tb.time_of_cycle_time(count + 1);
    EXPECT_EQ(b.read_at(step - 1, kTcnt), count + 1) << mhz;
    EXPECT_EQ(b.read_at(step, kTcnt), count + 2) << mhz;
  }
}

// docs/timing.md, "Cycle-time events": a cycle start's listeners hear the counter as it reads then:
// TCNTST after a load (the time base does not count ticks for it: the first one is at least
// an edge away, whatever MCLKST), TCNTST - TSCYC moved on for a substitute cycle.
TEST(TimeBase, CycleStartListenersHearTheCounterAsItReads) {
  for (const std::int64_t mclkst : {0, 1, 7}) {
    TimingBench b(config_mhz(32));
    b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>(mclkst << 8 | 31));
    b.chip.reg_write(kTcntst, 9);
    b.chip.reg_write(kTscyc0, 50);
    struct Heard {
      TimeBase* time_base;
      std::vector<std::pair<CycleKind, std::int64_t>> starts;
      static void hear(void* heard, const CycleStart& start) {
        auto& h = *static_cast<Heard*>(heard);
        EXPECT_EQ(start.count, h.time_base->count());
        h.starts.emplace_back(start.kind, start.count);
      }
    } heard{&b.time_base(), {}};
    b.time_base().on_cycle_start(&heard, &Heard::hear);
    b.run_to(10 * kMicrosecond + 5);  // between MCLK edges
    b.cycles().mst_detected(b.now());
    b.run_to(100 * kMicrosecond);  // the window closes empty: a substitute cycle
    ASSERT_GE(heard.starts.size(), 2u) << mclkst;
    EXPECT_EQ(heard.starts[0], std::make_pair(CycleKind::Mst, std::int64_t{9})) << mclkst;
    EXPECT_EQ(heard.starts[1].first, CycleKind::Substitute) << mclkst;
  }
}

// Listeners are fixed before the first cycle start (the time base walks them without
// looking back at their vector): one added from a listener is refused, the others still run.
TEST(TimeBase, NoListenerIsAddedDuringACycleStart) {
  TimingBench b(config_mhz(32));
  b.chip.reg_write(kTscyc0, 50);
  struct Adder {
    TimeBase* time_base;
    int refused = 0;
    int heard = 0;
    static void hear(void* adder, const CycleStart&) {
      auto& a = *static_cast<Adder*>(adder);
      ++a.heard;
      try {
        a.time_base->on_cycle_start(adder, &Adder::hear);
      } catch (const std::logic_error&) {
        ++a.refused;
      }
    }
  } adder{&b.time_base()};
  b.time_base().on_cycle_start(&adder, &Adder::hear);
  b.run_to(10 * kMicrosecond + 5);
  b.cycles().mst_detected(b.now());
  b.run_to(20 * kMicrosecond);
  EXPECT_GE(adder.heard, 1);
  EXPECT_EQ(adder.refused, adder.heard);
  b.time_base().on_cycle_start(&adder, &Adder::hear);  // outside a cycle start: taken
}

// An idle listener is not called; one woken or idled during a cycle start is called or not
// as its flag says at its turn (the time base walks only the range from the first listener
// not idle to the last, which a wake during the start widens).
TEST(TimeBase, ListenersWokenDuringACycleStartAreCalledAtTheirTurn) {
  TimingBench b(config_mhz(32));
  b.chip.reg_write(kTscyc0, 50);
  struct Listener {
    TimeBase* time_base;
    std::vector<int>* log;
    int me;
    std::vector<TimeBase::CycleListenerId>* ids;
    static void hear(void* listener, const CycleStart&) {
      auto& l = *static_cast<Listener*>(listener);
      l.log->push_back(l.me);
      const auto& ids = *l.ids;
      if (l.me == 1) {  // wakes the last (its turn to come) and the first (passed)
        l.time_base->set_cycle_listener_idle(ids[3], false);
        l.time_base->set_cycle_listener_idle(ids[0], false);
      }
      if (l.me == 3) {  // idles itself and the first again
        l.time_base->set_cycle_listener_idle(ids[3], true);
        l.time_base->set_cycle_listener_idle(ids[0], true);
      }
    }
  };
  std::vector<int> log;
  std::vector<TimeBase::CycleListenerId> ids;
  std::vector<Listener> listeners;
  for (int i = 0; i < 4; ++i) listeners.push_back(Listener{&b.time_base(), &log, i, &ids});
  for (Listener& l : listeners) ids.push_back(b.time_base().on_cycle_start(&l, &Listener::hear));
  for (const std::size_t i : {0u, 2u, 3u}) b.time_base().set_cycle_listener_idle(ids[i], true);
  b.run_to(10 * kMicrosecond + 5);
  b.cycles().mst_detected(b.now());
  b.run_to(20 * kMicrosecond);
  // Every start (the free-wheel's too) the same: 0 woken after its turn, 3 before its own.
  const auto each_start = [&log](std::vector<int> pattern) {
    std::vector<int> all;
    while (all.size() < log.size()) all.insert(all.end(), pattern.begin(), pattern.end());
    return all;
  };
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log, each_start({1, 3}));
  log.clear();
  b.time_base().set_cycle_listener_idle(ids[2], false);
  b.cycles().mst_detected(b.now());
  b.run_to(30 * kMicrosecond);
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log, each_start({1, 2, 3}));
}

// The function + context form (no std::function) keeps the same times, order and slots
// as the callback form, and a slot it used serves a callback event afterwards.
TEST(TimeBase, CycleTimeActionsRunLikeCallbacks) {
  TimingBench b(config_mhz(25));
  b.chip.reg_write(kClockDiv, 3 << 8 | 24);
  b.chip.reg_write(kTcntst, 2);
  b.run_to(5 * kMicrosecond);
  b.cycles().mst_detected(b.now());
  b.run_to(6 * kMicrosecond);
  auto& tb = b.time_base();
  std::vector<std::pair<char, Time>> ran;
  struct Mark {
    std::vector<std::pair<char, Time>>* ran;
    TimingBench* bench;
    static void run(void* mark) {
      auto& m = *static_cast<Mark*>(mark);
      m.ran->emplace_back('a', m.bench->now());
    }
  } mark{&ran, &b};
  const auto action = tb.at_cycle_time(20, &Mark::run, &mark);
  tb.at_cycle_time(20, [&] { ran.emplace_back('c', b.now()); });
  EXPECT_EQ(tb.at_cycle_time(1, &Mark::run, &mark),
            TimeBase::CycleEvent{});  // before TCNTST: never
  ASSERT_TRUE(tb.when(action).has_value());
  const Time due = *tb.when(action);
  b.run_to(100 * kMicrosecond);
  EXPECT_EQ(ran, (std::vector<std::pair<char, Time>>{{'a', due}, {'c', due}}));
  EXPECT_EQ(tb.when(action), std::nullopt);
  const auto reused = tb.at_cycle_time(150, [&] { ran.emplace_back('d', b.now()); });
  tb.cancel(action);  // stale: cancels nothing
  EXPECT_TRUE(tb.when(reused).has_value());
  b.run_to(1000 * kMicrosecond);
  EXPECT_EQ(ran.size(), 3u);
}

// Ids stay valid names: one that ran or was cancelled never names a later event (the
// slot it used is reused), and events at one time run in the order they were asked for,
// also when an MCLKDIV change moves them all.
TEST(TimeBase, CycleEventIdsAreNeverReusedAndOrderIsKept) {
  TimingBench b(config_mhz(25));
  b.chip.reg_write(kClockDiv, 3 << 8 | 24);
  b.run_to(5 * kMicrosecond);
  b.cycles().mst_detected(b.now());
  b.run_to(6 * kMicrosecond);
  auto& tb = b.time_base();
  std::vector<char> ran;
  const auto first = tb.at_cycle_time(10, [&] { ran.push_back('a'); });
  const auto second = tb.at_cycle_time(20, [&] { ran.push_back('b'); });
  ASSERT_NE(first, TimeBase::CycleEvent{});
  tb.cancel(first);
  const auto third = tb.at_cycle_time(20, [&] { ran.push_back('c'); });  // first's slot
  EXPECT_NE(third, first);
  tb.cancel(first);  // stale: cancels nothing
  EXPECT_EQ(tb.when(first), std::nullopt);
  ASSERT_TRUE(tb.when(third).has_value());
  EXPECT_EQ(tb.when(second), tb.when(third));
  b.chip.reg_write(kClockDiv, 3 << 8 | 49);  // 2 µs ticks: both move
  EXPECT_GT(*tb.when(third), 0);
  b.run_to(100 * kMicrosecond);
  EXPECT_EQ(ran, (std::vector<char>{'b', 'c'}));
  EXPECT_EQ(tb.when(second), std::nullopt);
  EXPECT_EQ(tb.when(third), std::nullopt);
  const auto fourth = tb.at_cycle_time(200, [&] { ran.push_back('d'); });
  tb.cancel(third);
  tb.cancel(second);
  EXPECT_TRUE(tb.when(fourth).has_value());
  b.run_to(1000 * kMicrosecond);
  EXPECT_EQ(ran, (std::vector<char>{'b', 'c', 'd'}));
}

// Register table: TSCYC0 for phases 0..2, TSCYC1 for 3..4 (phase = low 3 bits of PHAS0 for
// a master; a slave takes the phase byte of the MST it received, PHASR).
TEST(TimeBase, CycleTimeFollowsThePhase) {
  TimingBench b;
  b.chip.reg_write(kTscyc0, 2000);
  b.chip.reg_write(kTscyc1, 1000);
  b.chip.reg_write(kSerMode, kRegmode);
  for (std::uint16_t phase = 0; phase < 8; ++phase) {
    b.chip.reg_write(kPhase, phase);
    EXPECT_EQ(b.time_base().tscyc(), phase <= 2 ? 2000 : 1000) << phase;
  }
  b.chip.reg_write(kPhase, 0x84);  // bit 7 set: still phase 4
  EXPECT_EQ(b.time_base().tscyc(), 1000);
  b.chip.reg_write(kSerMode, 0);  // slave: PHASR (0 here)
  EXPECT_EQ(b.time_base().tscyc(), 2000);
  b.chip.regs().put(0x0A, 0xFF00, 0x0300);  // the telegram processor stores MST byte 3
  EXPECT_EQ(b.time_base().tscyc(), 1000);
}

}  // namespace
}  // namespace sercon::chip
