// TxD1-6 (datasheet Table 1: "TxD1 ... can be switched to a high impedance state"; "TxD6-2
// ... either output the serial data or can be used as parallel output ports. When they
// output transmit data, each pin can be switched to a high impedance state individually"),
// register 0x02 TXOE / TXLIGHT, 0x0B PORTSEL / PORTVAL, 0x01 POLTXD, and the test
// generator (delta spec 2.3.3: continuous light, zero bit stream).
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::kPoltxd;
using testing::kSerCtrl;
using testing::kSerMode;
using testing::kTmode0;
using testing::kTmode1;
using testing::kTmode2;
using testing::kTxLight;
using testing::kTxoe1;
using testing::kTxPort;
using testing::LineRecorder;
using testing::SerialBench;

const std::vector<std::uint8_t> kData = {0x12, 0x34, 0x56, 0x78};

// A recorder on each of TxD1-6.
struct AllOutputs {
  explicit AllOutputs(SerialBench& b) {
    for (unsigned n = 1; n <= 6; ++n) {
      recorders[n - 1] = std::make_unique<LineRecorder>(b.scheduler);
      b.unit.connect_txd(n, *recorders[n - 1]);
    }
  }
  LineRecorder& txd(unsigned n) { return *recorders[n - 1]; }
  std::array<std::unique_ptr<LineRecorder>, 6> recorders;
};

Level pin(SerialBench& b, unsigned n) { return b.chip->pin(txd_pin(n)).level(); }

// Register table: TXOE resets to 0, so after reset every TxD is high impedance and the
// fibres behind them are dark.
TEST(serial_TxdOutputs, AfterResetEveryOutputIsHighImpedanceAndDark) {
  SerialBench b;
  AllOutputs out(b);
  for (unsigned n = 1; n <= 6; ++n) {
    EXPECT_EQ(pin(b, n), Level::HighZ) << n;
    EXPECT_EQ(out.txd(n).last().condition, LineCondition::Dark) << n;
  }
}

// Datasheet Table 1: each data output "can be switched to a high impedance state
// individually" (TXOE bit n-1).
TEST(serial_TxdOutputs, EachOutputHasItsOwnHighImpedanceBit) {
  SerialBench b;
  AllOutputs out(b);
  b.chip->reg_write(kSerCtrl, static_cast<std::uint16_t>((1u << 2) | kTxLight));  // TxD3 only
  for (unsigned n = 1; n <= 6; ++n) {
    EXPECT_EQ(pin(b, n), n == 3 ? Level::High : Level::HighZ) << n;
    EXPECT_EQ(out.txd(n).last().condition, n == 3 ? LineCondition::Idle : LineCondition::Dark) << n;
  }
}

// Register table TXLIGHT (facts §5: a driver switches its LED on with 0x007F and off by
// clearing 0x0040): a driven output with the transmitter off shows the no-light level and
// the fibre is dark; with POLTXD = 1 light is a low level on the pin, the fibre still
// carries light (docs/serial-and-ring.md, "Polarity").
TEST(serial_TxdOutputs, TxlightAndPolarity) {
  SerialBench b;
  b.chip->reg_write(kSerCtrl, kTxoe1);
  EXPECT_EQ(pin(b, 1), Level::Low);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
  b.light_up();
  EXPECT_EQ(pin(b, 1), Level::High);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
  b.set_sermode_bits(kPoltxd, true);
  EXPECT_EQ(pin(b, 1), Level::Low);  // inverted: light is low
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
  b.chip->reg_write(kSerCtrl, kTxoe1);
  EXPECT_EQ(pin(b, 1), Level::High);  // inverted: dark is high
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
}

// Datasheet Table 1: TxD6-2 "can be used as parallel output ports"; PORTSEL bit n-2 selects
// the port function, PORTVAL bit n-2 the level (register table). High impedance belongs to
// the data function, so TXOE does not switch a port pin off. TxD1 has no port function.
TEST(serial_TxdOutputs, PortModeDrivesPortvalWhateverTxoe) {
  SerialBench b;
  AllOutputs out(b);
  b.chip->reg_write(kTxPort, 0x0101);  // TxD2 port, level 1
  EXPECT_EQ(pin(b, 2), Level::High);
  EXPECT_EQ(out.txd(2).last().condition, LineCondition::Light);  // a high pin lights the LED
  b.chip->reg_write(kTxPort, 0x0001);
  EXPECT_EQ(pin(b, 2), Level::Low);
  EXPECT_EQ(out.txd(2).last().condition, LineCondition::Dark);
  b.set_sermode_bits(kPoltxd, true);  // the pin keeps PORTVAL; the LED now lights on low
  EXPECT_EQ(pin(b, 2), Level::Low);
  EXPECT_EQ(out.txd(2).last().condition, LineCondition::Light);
  b.chip->reg_write(kTxPort, 0x1F1F);  // all of TxD2-6 ports at 1
  for (unsigned n = 2; n <= 6; ++n) EXPECT_EQ(pin(b, n), Level::High) << n;
  EXPECT_EQ(pin(b, 1), Level::HighZ);
  b.chip->reg_write(kTxPort, 0x1F00);  // back to data: TXOE = 0, high impedance
  for (unsigned n = 2; n <= 6; ++n) EXPECT_EQ(pin(b, n), Level::HighZ) << n;
}

// A data output switched off in the middle of a telegram cuts it: the fibre sees Dark at
// that moment (line contract: a new condition before burst.end() ends the burst).
TEST(serial_TxdOutputs, SwitchingOffMidTelegramCutsTheBurst) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  b.unit.send(10 * t, 0x01, kData);
  b.run_to(30 * t);
  b.chip->reg_write(kSerCtrl, 0);
  ASSERT_EQ(b.txd1.bursts().size(), 1u);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
  EXPECT_EQ(b.txd1.last().at, 30 * t);
  EXPECT_LT(b.txd1.last().at, b.txd1.bursts()[0].at + b.unit.burst_duration(0x01, kData));
}

// Delta spec 2.3.3 table, TM0 = 0, TM1 = 1: "TxD1-6 continues signal light"; the test
// signal overrides data: own telegrams do not reach the fibre (IDLE still shows that the
// transmitter sends, documented decision).
TEST(serial_TestGenerator, ContinuousLightFromThePinsOverridesData) {
  ChipConfig c;
  c.tm0 = false;
  c.tm1 = true;
  SerialBench b(c);
  b.light_up();
  const Time t = b.period();
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Light);
  EXPECT_EQ(pin(b, 1), Level::High);
  const Time end = b.unit.send(10 * t, 0x01, kData);
  b.run_to(11 * t);
  EXPECT_EQ(b.chip->pin(Pin::IDLE).level(), Level::Low);
  b.run_to(end + t);
  EXPECT_TRUE(b.txd1.bursts().empty());
}

// Delta spec 2.3.3: "The control bits TMODE2-0 can also over write the actual test mode.
// Coding for this control bits does not change": TMODE2 = 1 with TMODE0 = 1, TMODE1 = 0
// is the zero bit stream (TM0 = 1, TM1 = 0 row); with TMODE1 = 1 it is continuous light;
// with both 0 no test mode.
TEST(serial_TestGenerator, TmodeBitsSelectZeroBitsLightOrNone) {
  SerialBench b;
  const Time t = b.period();
  b.light_up(kTmode2 | kTmode0);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::ZeroBits);
  EXPECT_EQ(b.txd1.last().period, t);
  b.light_up(kTmode2 | kTmode1);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Light);
  b.light_up(kTmode2);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
  b.light_up(kTmode0);  // TMODE2 = 0: the pins (TM0 = TM1 = 1, none) rule
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
}

// TXLIGHT = 0 switches the optical transmitter off: no test light either (decision).
TEST(serial_TestGenerator, TransmitterOffStaysDarkInTestMode) {
  SerialBench b;
  b.chip->reg_write(kSerCtrl, static_cast<std::uint16_t>(kTxoe1 | kTmode2 | kTmode1));
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
}

// Test mode switched by the pins while running (TMODE2 = 0): the generator follows them.
TEST(serial_TestGenerator, FollowsTheTmPinsWhileRunning) {
  SerialBench b;
  b.light_up();
  b.chip->drive(Pin::TM0, Level::Low);  // TM0 = 0, TM1 = 1: continuous light
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Light);
  b.chip->drive(Pin::TM1, Level::Low);  // 0 0: none
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
}

// Counts what it is told, raw (no SettledLine).
struct JoinCounter final : LineListener {
  void line_condition(Time, LineCondition, Time) override { ++conditions; }
  void line_burst(const LineBurst& b) override { starts.push_back(b.start); }
  int conditions = 0;
  std::vector<Time> starts;
};

// On its first burst, connects `late` to TxD `pin` of `unit` (a listener joining from
// inside a callback of the TxD line).
struct JoinInCallback final : LineListener {
  JoinInCallback(SerialUnit& u, unsigned p, LineListener& l) : unit(u), pin(p), late(l) {}
  void line_condition(Time, LineCondition, Time) override {}
  void line_burst(const LineBurst&) override {
    if (done) return;
    done = true;
    unit.connect_txd(pin, late);
  }
  SerialUnit& unit;
  unsigned pin;
  LineListener& late;
  bool done = false;
};

// TxD2 and TxD3 follow the line (TxD1 off). The only listener, on TxD2, connects another to
// TxD3 while it is told of a burst. The newcomer is told the line as it joins, the burst
// included (tell_line), and not told that burst a second time (decision,
// docs/serial-and-ring.md "TxD1-6": each announcement is heard once). Before
// the lone follower (d1d5dec) the walk over the six outputs told it twice.
TEST(serial_TxdOutputs, AListenerJoiningInsideACallbackIsToldTheBurstOnce) {
  testing::SerialBench b;
  b.chip->reg_write(kSerCtrl, static_cast<std::uint16_t>((1u << 1) | (1u << 2) | kTxLight));
  JoinCounter late;
  JoinInCallback hook(b.unit, 3, late);
  b.unit.connect_txd(2, hook);
  const Time t = b.period();
  const Time end = b.unit.send(10 * t, 0x01, std::vector<std::uint8_t>{0x11, 0x22});
  b.run_to(end + 20 * t);
  ASSERT_TRUE(hook.done);
  EXPECT_EQ(late.starts, (std::vector<Time>{10 * t}));
}

// A listener taken off a TxD pin (disconnect_txd, or connect_txd of another listener to the
// same pin) is no longer lit by the chip: it is told Dark at once, and the receiver behind
// it raises FIBBR, as when the pin goes to high impedance (TXOE bit 0 = 0, the control)
// (review wt-a4).
enum class Unplug { Txoe, Disconnect, ConnectOther };
bool far_fibbr_after(Unplug how) {
  sim::Scheduler s;
  Chip tx(s, ChipConfig{});
  Chip rx(s, ChipConfig{});
  tx.reg_write(kSerMode, static_cast<std::uint16_t>(tx.reg_read(kSerMode) & ~testing::kRepon));
  tx.reg_write(kSerCtrl, static_cast<std::uint16_t>(kTxoe1 | kTxLight));  // the own idle fill
  auto& unit = *tx.unit<SerialUnit>();
  const Time t = unit.bit_period();
  LineRecorder other(s);
  unit.connect_txd(1, rx.unit<SerialUnit>()->rxd());
  s.run_until(1000 * t);
  EXPECT_FALSE(rx.reg_read(kSerCtrl) & (1u << 13));
  switch (how) {
    case Unplug::Txoe:
      tx.reg_write(kSerCtrl, kTxLight);
      break;
    case Unplug::Disconnect:
      unit.disconnect_txd(1);
      break;
    case Unplug::ConnectOther:
      unit.connect_txd(1, other);
      break;
  }
  s.run_until(2000 * t);
  return (rx.reg_read(kSerCtrl) & (1u << 13)) != 0;
}

TEST(serial_TxdOutputs, AFibreTakenOffATxdPinGoesDark) {
  EXPECT_TRUE(far_fibbr_after(Unplug::Txoe));  // control
  EXPECT_TRUE(far_fibbr_after(Unplug::Disconnect)) << "disconnect_txd: the listener stays lit";
  EXPECT_TRUE(far_fibbr_after(Unplug::ConnectOther))
      << "connect_txd on a connected pin: the first listener stays lit";
}

// The listener left is told Dark at the moment it leaves; one still driven by another pin,
// or connected again to the same pin, is not.
TEST(serial_TxdOutputs, AListenerLeftIsToldDarkUnlessStillDriven) {
  SerialBench b;
  b.chip->reg_write(kSerCtrl, static_cast<std::uint16_t>(kTxoe1 | (1u << 1) | kTxLight));
  const Time t = b.period();
  LineRecorder shared(b.scheduler);
  b.unit.connect_txd(2, shared);
  b.run_to(100 * t);
  b.unit.connect_txd(1, b.txd1);  // the same listener again
  ASSERT_FALSE(b.txd1.events.empty());
  EXPECT_NE(b.txd1.events.back().condition, LineCondition::Dark);
  b.unit.connect_txd(1, shared);  // txd1 replaced; shared now on TxD1 and TxD2
  b.run_to(100 * t);
  EXPECT_EQ(b.txd1.events.back().condition, LineCondition::Dark);
  EXPECT_EQ(b.txd1.events.back().at, 100 * t);
  b.run_to(200 * t);
  b.unit.disconnect_txd(2);  // still driven by TxD1
  b.run_to(200 * t);
  EXPECT_NE(shared.events.back().condition, LineCondition::Dark);
  b.unit.disconnect_txd(1);
  b.run_to(200 * t);
  EXPECT_EQ(shared.events.back().condition, LineCondition::Dark);
  EXPECT_EQ(shared.events.back().at, 200 * t);
}

}  // namespace
}  // namespace sercon::chip
