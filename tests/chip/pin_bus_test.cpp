// The bus driven through pins: Intel and Motorola strobes (Table 1 RDN, WRN, BUSMODE1-0),
// the multiplexed address latch (ADMUX, ALEL, ALEH; datasheet 3.5.3), data lines driven
// only while a read strobe is active (datasheet 3.5.4: t_RDZ, D15-0 high-Z after RDN).
#include "sercon/chip/pin_bus.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "chip_fixture.hpp"
#include "sercon/chip/dma_port.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::ChipOnBench;

class PinBusTest : public ::testing::Test {
 protected:
  Chip& chip() { return *bench.chip; }
  void set(Pin p, bool high) { chip().drive(p, sim::level_of(high)); }
  void address(std::uint16_t a) {
    for (unsigned bit = 0; bit < 16; ++bit) set(address_pin(bit), ((unsigned{a} >> bit) & 1u) != 0);
  }
  void data(std::uint16_t d) {
    for (unsigned bit = 0; bit < 16; ++bit) set(data_pin(bit), ((unsigned{d} >> bit) & 1u) != 0);
  }
  void float_data() {
    for (unsigned bit = 0; bit < 16; ++bit) chip().drive(data_pin(bit), Level::HighZ);
  }
  std::uint16_t data_lines() {
    std::uint16_t d = 0;
    for (unsigned bit = 0; bit < 16; ++bit) {
      if (chip().input_high(data_pin(bit))) d = static_cast<std::uint16_t>(d | 1u << bit);
    }
    return d;
  }
  bool any_data_driven() {
    for (unsigned bit = 0; bit < 16; ++bit) {
      if (chip().drives(data_pin(bit))) return true;
    }
    return false;
  }
  void select_registers(bool on) {
    set(Pin::PCSN0, !on);
    set(Pin::PCS1, on);
  }
  void select_ram(bool on) {
    set(Pin::MCSN0, !on);
    set(Pin::MCSN1, !on);
  }
  // Runs `change` then `drive` as one step (one scheduler event: watchers hear the pin
  // changes when it is done, sim/signal.hpp) and says whether the chip refused a line the
  // board drives in `drive` (std::invalid_argument).
  bool refused_in_one_step(const std::function<void()>& change,
                           const std::function<void()>& drive) {
    bool refused = false;
    bench.scheduler.at(50'000, [&] {
      change();
      try {
        drive();
      } catch (const std::invalid_argument&) {
        refused = true;
      }
    });
    bench.scheduler.run_until(60'000);
    return refused;
  }

  ChipOnBench bench;
};

// Intel: "data is read when RDN is 0", "written to when WRN is 0".
TEST_F(PinBusTest, IntelReadDrivesDataWhileRdnIsLow) {
  set(Pin::BHEN, false);
  address(0x0000);
  select_registers(true);
  set(Pin::RDN, false);
  EXPECT_EQ(data_lines(), 0x0010);  // VERSION
  EXPECT_TRUE(any_data_driven());
  EXPECT_THROW(chip().drive(Pin::D4, Level::Low), std::invalid_argument);  // contention
  set(Pin::RDN, true);
  EXPECT_FALSE(any_data_driven());
  EXPECT_EQ(chip().pin(Pin::D4).level(), Level::HighZ);
}

// Table 1 WRN; datasheet 3.5.6 "setup time D15-0 to end of write access" and docs/chip.md
// "The bus through the pins": a write takes D15-0 when the strobe ends.
TEST_F(PinBusTest, IntelWriteTakesDataAtTheEndOfWrn) {
  set(Pin::BHEN, false);
  address(0x0014);  // register 0x0A
  select_registers(true);
  set(Pin::WRN, false);
  data(0x0003);
  EXPECT_EQ(chip().reg_read(0x0A), 0);  // nothing yet
  set(Pin::WRN, true);
  EXPECT_EQ(chip().reg_read(0x0A), 0x0003);
}

// Motorola, BUSMODE1 = 0: RDN is a 0-active data strobe, WRN = 1 read / 0 write.
TEST_F(PinBusTest, MotorolaLowActiveStrobe) {
  set(Pin::BUSMODE0, true);
  set(Pin::BHEN, false);
  address(0x0020);  // RAM word 0x10
  select_ram(true);
  set(Pin::WRN, false);
  data(0xBEEF);
  set(Pin::RDN, false);
  set(Pin::RDN, true);
  EXPECT_EQ(chip().ram().read(0x10), 0xBEEF);
  float_data();
  set(Pin::WRN, true);
  set(Pin::RDN, false);
  EXPECT_EQ(data_lines(), 0xBEEF);
  set(Pin::RDN, true);
  EXPECT_FALSE(any_data_driven());
}

// Motorola, BUSMODE1 = 1: the data strobe is 1-active.
TEST_F(PinBusTest, MotorolaHighActiveStrobe) {
  set(Pin::RDN, false);  // inactive for a 1-active strobe
  set(Pin::BUSMODE0, true);
  set(Pin::BUSMODE1, true);
  set(Pin::BHEN, false);
  address(0x0000);
  select_registers(true);
  set(Pin::RDN, true);
  EXPECT_EQ(data_lines(), 0x0010);
  set(Pin::RDN, false);
  EXPECT_FALSE(any_data_driven());
}

// ADMUX = 1: "A15-0 are the outputs of the address latch"; ALEL / ALEH = 1 pass D7-0 /
// D15-8 through, 0 stores them.
TEST_F(PinBusTest, MultiplexedAddressLatch) {
  set(Pin::ADMUX, true);
  set(Pin::BHEN, false);
  data(0x0014);  // address phase: register 0x0A
  set(Pin::ALEL, false);
  set(Pin::ALEH, false);
  EXPECT_EQ(chip().unit<PinBus>()->latched_address(), 0x0014);
  EXPECT_EQ(chip().pin(Pin::A2).level(), Level::High);  // latch drives A15-0
  EXPECT_THROW(chip().drive(Pin::A2, Level::Low), std::invalid_argument);
  data(0x0004);  // data phase: the latch holds
  select_registers(true);
  set(Pin::WRN, false);
  set(Pin::WRN, true);
  EXPECT_EQ(chip().reg_read(0x0A), 0x0004);
  set(Pin::ADMUX, false);  // A15-0 become inputs again
  EXPECT_FALSE(chip().drives(Pin::A2));
}

// Datasheet 3.5.3: the latch stores D15-0 at the falling edge of ALEL / ALEH (hold
// T_ALEHD). A multiplexed µP modelled as one event that puts the address on D15-0, closes
// the latch and goes on to the data phase latches the address, as the same changes made
// one by one do: the latch follows the lines as they were at each change.
TEST_F(PinBusTest, LatchInOneStepTakesTheAddressPhase) {
  set(Pin::ADMUX, true);
  set(Pin::BHEN, false);
  bench.scheduler.at(50'000, [this] {
    data(0x0014);  // address phase: register 0x0A
    set(Pin::ALEL, false);
    set(Pin::ALEH, false);
    data(0x0004);  // data phase
  });
  bench.scheduler.run_until(60'000);
  EXPECT_EQ(chip().unit<PinBus>()->latched_address(), 0x0014);
  select_registers(true);
  set(Pin::WRN, false);
  set(Pin::WRN, true);
  EXPECT_EQ(chip().reg_read(0x0A), 0x0004);
}

// docs/chip.md "Pins": the board may not drive a data line the chip drives "at that
// moment (a read in progress)"; the chip floats D15-0 at once when RDN rises (decision,
// "The bus through the pins"). A board that ends a read and puts the next write's data on
// D15-0 in one step (a scheduler event, a pin callback) drives the lines as it does when
// it makes the same changes one by one: the read is no longer in progress.
TEST_F(PinBusTest, EndingAReadAndDrivingDataInOneStep) {
  set(Pin::BHEN, false);
  address(0x0014);  // register 0x0A
  select_registers(true);
  set(Pin::RDN, false);
  ASSERT_TRUE(any_data_driven());
  EXPECT_FALSE(refused_in_one_step([this] { set(Pin::RDN, true); },
                                   [this] {
                                     data(0x0003);
                                     set(Pin::WRN, false);
                                   }));
  EXPECT_EQ(data_lines(), 0x0003);
  set(Pin::WRN, true);
  EXPECT_EQ(chip().reg_read(0x0A), 0x0003);
}

// The same for A15-0: ADMUX = 0 makes them inputs again ("The bus through the pins").
TEST_F(PinBusTest, LeavingAdmuxAndDrivingTheAddressInOneStep) {
  set(Pin::ADMUX, true);
  data(0x0014);
  set(Pin::ALEL, false);
  ASSERT_TRUE(chip().drives(Pin::A2));
  EXPECT_FALSE(
      refused_in_one_step([this] { set(Pin::ADMUX, false); }, [this] { address(0x0000); }));
  EXPECT_FALSE(chip().drives(Pin::A2));
  EXPECT_EQ(chip().pin(Pin::A2).level(), Level::Low);
}

// Table 1 OUTZ: "OUTZ is 1 puts all pins into a high impedance state". A board that raises
// OUTZ during a read and drives D15-0 in the same step drives them, as it may when it
// makes the two changes one by one.
TEST_F(PinBusTest, RaisingOutzAndDrivingDataInOneStep) {
  set(Pin::BHEN, false);
  address(0x0000);
  select_registers(true);
  set(Pin::RDN, false);
  ASSERT_TRUE(any_data_driven());
  EXPECT_FALSE(refused_in_one_step([this] { set(Pin::OUTZ, true); }, [this] { data(0x1234); }));
  EXPECT_EQ(data_lines(), 0x1234);
}

// Decision (docs/chip.md, bus: "both at once would make two drivers fight on D15-0"):
// selecting RAM and registers at once is a board fault: the strobe makes no access.
TEST_F(PinBusTest, DoubleSelectIsRefused) {
  set(Pin::BHEN, false);
  address(0x0000);
  select_registers(true);
  select_ram(true);
  set(Pin::RDN, false);
  EXPECT_FALSE(any_data_driven());
  set(Pin::RDN, true);
  EXPECT_EQ(chip().unit<PinBus>()->refused_cycles(), 1u);
}

// Table 1, DMAACKRN: "the receive FIFO is read, independent of the levels on A6-1 and
// the chip select signals": such a strobe is no RAM or register access. With VERSION
// (0x0010, datasheet 4.1) addressed and selected, the lines carry the FIFO's word; with
// the FIFO empty they carry nothing (an underrun, docs/telegram-processing.md "DMA").
TEST_F(PinBusTest, DmaAcknowledgeBypassesRamAndRegisters) {
  set(Pin::BHEN, false);
  address(0x0000);
  select_registers(true);
  set(Pin::DMAACKRN, false);
  set(Pin::RDN, false);
  EXPECT_FALSE(any_data_driven());
  set(Pin::RDN, true);
  chip().reg_write(0x0C, 0x0001);  // DMACTRL.DMARXEN (docs/registers.md)
  const std::uint16_t word = 0x1234;
  chip().unit<DmaPort>()->receive(std::span(&word, 1));
  set(Pin::RDN, false);
  EXPECT_TRUE(any_data_driven());
  EXPECT_EQ(data_lines(), 0x1234);  // the FIFO word, not VERSION
  set(Pin::RDN, true);
  EXPECT_FALSE(any_data_driven());
  EXPECT_EQ(chip().unit<DmaPort>()->receive_count(), 0u);  // the read took it
}

// Table 1 BHEN ("data is transferred via D15-8 when BHEN is 0") and docs/chip.md (a byte
// lane not in use is not driven; the lines read 1 through the pull-ups, datasheet 3.3): a
// byte read (BHEN = 1, A0 = 0) on a 16-bit bus drives only D7-0.
TEST_F(PinBusTest, ByteReadDrivesOneLane) {
  chip().ram_write(0, 0x1234);
  set(Pin::BHEN, true);
  address(0x0000);
  select_ram(true);
  set(Pin::RDN, false);
  EXPECT_TRUE(chip().drives(Pin::D0));
  EXPECT_FALSE(chip().drives(Pin::D8));
  EXPECT_EQ(data_lines(), 0xFF34);
  set(Pin::RDN, true);
}

// Datasheet 3.5.7 (and 3.5.6) t_AHD: the hold time of A11-0, BHEN and MCSN0-1 after the
// rising edge of WRN is 0 ns, so a board may end the write and move on to the next cycle's
// address and selects at the same instant. A board model does that in one scheduler event
// (or one pin callback); the chip reacts to each pin change at once (sim/signal.hpp), so
// the write still goes where the pins pointed when WRN rose.
TEST_F(PinBusTest, WriteEndTakesTheAddressAsItWasAtTheStrobeEnd) {
  set(Pin::BHEN, false);
  address(0x0020);  // RAM word 0x10
  select_ram(true);
  set(Pin::WRN, false);
  data(0xBEEF);
  bench.scheduler.at(50'000, [this] {
    set(Pin::WRN, true);  // end of the write
    address(0x0040);      // next cycle's address, RAM word 0x20 (hold 0 ns)
    set(Pin::BHEN, true);
  });
  bench.scheduler.run_until(60'000);
  EXPECT_EQ(chip().ram().read(0x10), 0xBEEF);
  EXPECT_EQ(chip().ram().read(0x20), 0);
}

TEST_F(PinBusTest, WriteEndTakesTheChipSelectsAsTheyWereAtTheStrobeEnd) {
  set(Pin::BHEN, false);
  address(0x0014);  // register 0x0A (PHAS0) or RAM word 0x0A
  select_registers(true);
  set(Pin::WRN, false);
  data(0x0003);
  bench.scheduler.at(50'000, [this] {
    set(Pin::WRN, true);      // end of the register write
    select_registers(false);  // deselected at the same instant (t_AHD PCSN0, PCS1: 0 ns)
    select_ram(true);
  });
  bench.scheduler.run_until(60'000);
  EXPECT_EQ(chip().reg_read(0x0A), 0x0003);
  EXPECT_EQ(chip().ram().read(0x0A), 0);
}

// BUSYN for strobes over a RAM word the telegram processor uses in the same MCLK period
// (Table 1 BUSYN). Datasheet 3.5.7: t_MBSY "Delay WRN or RDN (begin of write access) to
// BUSYN low" max 15 ns, t_MBHWH "Setup time BUSYN high to end of write access" min 15 ns;
// 3.5.5: t_MBSY "delay RDN to BUSYN low". MCLK 32 MHz: period 3 runs 93 750 .. 125 000 ps,
// period 5 156 250 .. 187 500 ps.
class PinBusBusyn : public PinBusTest {
 protected:
  PinBusBusyn() {
    chip().pin(Pin::BUSYN).watch([this](Level l) { edges.emplace_back(bench.scheduler.now(), l); });
    set(Pin::BHEN, false);
    address(0x0123 * 2);
    select_ram(true);
  }
  Level busyn() { return chip().pin(Pin::BUSYN).level(); }

  std::vector<std::pair<Time, Level>> edges;
};

// Control: a read's collision is the strobe start's.
TEST_F(PinBusBusyn, ReadStrobeCollisionPullsBusynAtTheStrobeStart) {
  bench.scheduler.run_until(100'000);
  chip().tp_ram_write(0x0123, 0x4444);
  set(Pin::RDN, false);  // the read begins in the same MCLK period
  EXPECT_EQ(busyn(), Level::Low);
  EXPECT_EQ(data_lines(), 0x4444);
  bench.scheduler.run_until(110'000);
  set(Pin::RDN, true);
  bench.scheduler.run_until(200'000);
  using E = std::pair<Time, Level>;
  EXPECT_EQ(edges, (std::vector<E>{{100'000, Level::Low}, {125'000, Level::High}}));
}

TEST_F(PinBusBusyn, WriteStrobeCollisionPullsBusynAtTheStrobeStart) {
  data(0xBEEF);
  bench.scheduler.run_until(100'000);
  chip().tp_ram_write(0x0123, 0x4444);           // the telegram processor uses word 0x123
  set(Pin::WRN, false);                          // the µP's write to it begins in the same period
  EXPECT_EQ(busyn(), Level::Low);                // t_MBSY
  EXPECT_EQ(chip().ram().read(0x0123), 0x4444);  // the data is not taken yet
  bench.scheduler.run_until(160'000);
  set(Pin::WRN, true);  // the end of the write, two MCLK periods later
  bench.scheduler.run_until(200'000);
  using E = std::pair<Time, Level>;
  // High again at the next MCLK edge, 35 ns before the end (t_MBHWH), and not again.
  EXPECT_EQ(edges, (std::vector<E>{{100'000, Level::Low}, {125'000, Level::High}}));
  EXPECT_EQ(chip().ram().read(0x0123), 0xBEEF);
  EXPECT_TRUE(chip().unit<PinBus>()->last_result().busy);
}

// A write strobe that ends inside the collision period: BUSYN fell at its start and does
// not fall (again) at its end.
TEST_F(PinBusBusyn, ShortWriteStrobeCollisionDoesNotDropBusynAtTheStrobeEnd) {
  data(0xBEEF);
  bench.scheduler.run_until(95'000);
  chip().tp_ram_write(0x0123, 0x4444);
  set(Pin::WRN, false);
  bench.scheduler.run_until(120'000);  // t_MWRW = 25 ns >= 20 ns
  set(Pin::WRN, true);
  bench.scheduler.run_until(200'000);
  using E = std::pair<Time, Level>;
  EXPECT_EQ(edges, (std::vector<E>{{95'000, Level::Low}, {125'000, Level::High}}));
  EXPECT_EQ(chip().ram().read(0x0123), 0xBEEF);
}

// The telegram processor uses the word in the period the write ends in, not the one it
// began in: no collision, as BUSYN must be high before the end of the write (t_MBHWH).
TEST_F(PinBusBusyn, WriteStrobeEndDoesNotPullBusyn) {
  data(0xBEEF);
  bench.scheduler.run_until(100'000);
  set(Pin::WRN, false);
  bench.scheduler.run_until(160'000);
  chip().tp_ram_write(0x0123, 0x4444);
  bench.scheduler.run_until(170'000);
  set(Pin::WRN, true);
  bench.scheduler.run_until(200'000);
  EXPECT_TRUE(edges.empty());
  EXPECT_EQ(chip().ram().read(0x0123), 0xBEEF);
  EXPECT_FALSE(chip().unit<PinBus>()->last_result().busy);
}

// A register read in progress through a reset. docs/chip.md "Resets": every reset "sets
// every output inactive", D15-0 HighZ, and while RSTN = 0 or OUTZ = 1 reads give reset
// values; Table 1 OUTZ: "the circuit is reset". A read samples its word when the strobe
// starts, so after the reset a strobe still held drives nothing; a new strobe reads the
// register as it now is. PHAS0 (0x0A) = 3 before the reset, 0 after it.
class PinBusReset : public PinBusTest {
 protected:
  PinBusReset() {
    chip().reg_write(0x0A, 3);
    set(Pin::BHEN, false);
    address(0x0A * 2);
    select_registers(true);
  }
};

// Control: a read strobe that begins after the reset reads the reset value.
TEST_F(PinBusReset, ReadAfterResetShowsTheResetValue) {
  chip().drive(Pin::OUTZ, Level::High);
  chip().drive(Pin::OUTZ, Level::Low);
  set(Pin::RDN, false);
  EXPECT_TRUE(any_data_driven());
  EXPECT_EQ(data_lines(), 0);
  set(Pin::RDN, true);
}

TEST_F(PinBusReset, OutzPulseDuringAReadDoesNotDriveThePreResetValue) {
  set(Pin::RDN, false);
  ASSERT_EQ(data_lines(), 3);
  chip().drive(Pin::OUTZ, Level::High);  // the circuit is reset
  chip().drive(Pin::OUTZ, Level::Low);
  ASSERT_EQ(chip().reg_read(0x0A), 0);
  EXPECT_FALSE(any_data_driven()) << "D15-0 driven with 0x" << std::hex << data_lines();
  EXPECT_EQ(data_lines(), 0xFFFF);  // floating, pulled up
  set(Pin::RDN, true);
  set(Pin::RDN, false);  // a new read
  EXPECT_EQ(data_lines(), 0);
  set(Pin::RDN, true);
  EXPECT_FALSE(any_data_driven());
}

TEST_F(PinBusReset, RstnDuringAReadDoesNotKeepDrivingThePreResetValue) {
  set(Pin::RDN, false);
  ASSERT_EQ(data_lines(), 3);
  chip().drive(Pin::RSTN, Level::Low);  // registers now held at their reset values
  EXPECT_FALSE(any_data_driven()) << "D15-0 driven with 0x" << std::hex << data_lines();
  EXPECT_NO_THROW(chip().drive(Pin::D0, Level::Low));  // the lines are free for the board
  chip().drive(Pin::D0, Level::HighZ);
  set(Pin::RDN, true);
  set(Pin::RDN, false);  // a new read in reset gives the reset value
  EXPECT_EQ(data_lines(), 0);
  set(Pin::RDN, true);
  chip().drive(Pin::RSTN, Level::High);
}

// docs/chip.md "Resets", decision: a write strobe the reset cut short writes nothing when
// it ends, as a read the reset cut short drives nothing and a DMA write the reset cut
// short moves no word (DmaPort): the reset aborted the access. RAM keeps its contents
// through the reset, so a RAM write shows it; a strobe that begins after the reset writes.
TEST_F(PinBusTest, AWriteStrobeHeldThroughAResetWritesNothingAtItsEnd) {
  chip().ram_write(0x0100, 0x1111);
  set(Pin::BHEN, false);
  address(0x0100 * 2);
  select_ram(true);
  set(Pin::WRN, false);
  data(0x2222);
  chip().drive(Pin::RSTN, Level::Low);
  chip().drive(Pin::RSTN, Level::High);
  set(Pin::WRN, true);
  float_data();
  EXPECT_EQ(chip().ram_read(0x0100), 0x1111);
  set(Pin::WRN, false);  // the next write goes in
  data(0x3333);
  set(Pin::WRN, true);
  float_data();
  EXPECT_EQ(chip().ram_read(0x0100), 0x3333);
}

}  // namespace
}  // namespace sercon::chip
