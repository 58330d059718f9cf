// The µP bus interface: chip selects, byte lanes, BUSWIDTH, BYTEDIR and BHEN
// (datasheet Table 1), address wrapping on the connected address lines (delta spec 2.5,
// datasheet 4.1 "A6-1"), and what an unselected or high-impedance chip reads as.
#include <gtest/gtest.h>

#include <stdexcept>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

ChipConfig bus_config(bool bus16, bool bytedir) {
  ChipConfig c;
  c.buswidth = bus16;
  c.bytedir = bytedir;
  return c;
}

BusCycle ram(std::uint16_t address, bool bhen, bool write = false, std::uint16_t data = 0) {
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.address = address;
  c.bhen = bhen;
  c.write = write;
  c.data = data;
  return c;
}

// --- 16-bit bus ------------------------------------------------------------------------

// Table 1, BUSWIDTH = 1: D15-0; BHEN = 0: D15-8 in use; A0 = 0: D7-0; BYTEDIR = 0: A0 = 0
// addresses the lower 8 bits of a word.
TEST(Bus16, WordAndByteLanesLowByteFirst) {
  ChipOnBench bench(bus_config(true, false));
  Chip& chip = *bench.chip;
  chip.bus(ram(0x0010, false, true, 0x1234));
  EXPECT_EQ(chip.ram().read(0x0008), 0x1234);

  BusResult r = chip.bus(ram(0x0010, false));  // word
  EXPECT_EQ(r.data, 0x1234);
  EXPECT_EQ(r.driven, 0xFFFF);
  r = chip.bus(ram(0x0010, true));  // A0 = 0, BHEN = 1: low byte on D7-0, D15-8 float
  EXPECT_EQ(r.data, 0xFF34);
  EXPECT_EQ(r.driven, 0x00FF);
  r = chip.bus(ram(0x0011, false));  // A0 = 1, BHEN = 0: high byte on D15-8
  EXPECT_EQ(r.data, 0x12FF);
  EXPECT_EQ(r.driven, 0xFF00);
  r = chip.bus(ram(0x0011, true));  // no lane in use
  EXPECT_EQ(r.data, 0xFFFF);
  EXPECT_EQ(r.driven, 0);

  chip.bus(ram(0x0010, true, true, 0xEEAB));  // low byte only
  EXPECT_EQ(chip.ram().read(0x0008), 0x12AB);
  chip.bus(ram(0x0011, false, true, 0xCDEE));  // high byte only
  EXPECT_EQ(chip.ram().read(0x0008), 0xCDAB);
  chip.bus(ram(0x0011, true, true, 0x0000));  // no lane: nothing written
  EXPECT_EQ(chip.ram().read(0x0008), 0xCDAB);
}

// BYTEDIR = 1: "the upper 8 bits of a word are addressed" by A0 = 0, which uses D7-0;
// a word access therefore carries the word's high byte on D7-0 (project reading of
// Table 1, docs/chip.md).
TEST(Bus16, HighByteFirstSwapsTheLanes) {
  ChipOnBench bench(bus_config(true, true));
  Chip& chip = *bench.chip;
  chip.ram_write(0x0008, 0x1234);
  EXPECT_EQ(chip.bus(ram(0x0010, false)).data, 0x3412);
  EXPECT_EQ(chip.bus(ram(0x0010, true)).data, 0xFF12);   // A0 = 0: high half
  EXPECT_EQ(chip.bus(ram(0x0011, false)).data, 0x34FF);  // A0 = 1: low half on D15-8
  chip.bus(ram(0x0010, true, true, 0x00AB));
  EXPECT_EQ(chip.ram().read(0x0008), 0xAB34);
  EXPECT_EQ(chip.ram_read(0x0008), 0xAB34);  // the word API gives the logical value
}

// --- 8-bit bus -------------------------------------------------------------------------

// Table 1: "for 8-bit-wide bus interfaces, data is written to and read via D7-0".
TEST(Bus8, LowByteFirst) {
  ChipOnBench bench(bus_config(false, false));
  Chip& chip = *bench.chip;
  chip.ram_write(0x0008, 0x1234);
  EXPECT_EQ(chip.bus(ram(0x0010, false)).data, 0xFF34);  // BHEN is ignored
  EXPECT_EQ(chip.bus(ram(0x0011, false)).data, 0xFF12);
  EXPECT_EQ(chip.bus(ram(0x0011, true)).driven, 0x00FF);
  chip.bus(ram(0x0011, true, true, 0xFFAB));  // D15-8 are not used
  EXPECT_EQ(chip.ram().read(0x0008), 0xAB34);
  EXPECT_EQ(chip.ram_read(0x0008), 0xAB34);
}

TEST(Bus8, HighByteFirst) {
  ChipOnBench bench(bus_config(false, true));
  Chip& chip = *bench.chip;
  chip.ram_write(0x0008, 0x1234);
  EXPECT_EQ(chip.bus(ram(0x0010, true)).data, 0xFF12);
  EXPECT_EQ(chip.bus(ram(0x0011, true)).data, 0xFF34);
  EXPECT_EQ(chip.ram_read(0x0008), 0x1234);
}

// The word API gives the same logical words in every bus mode, RAM and registers.
TEST(BusModes, WordApiIsTheSameInAllFourModes) {
  for (bool bus16 : {false, true}) {
    for (bool bytedir : {false, true}) {
      ChipOnBench bench(bus_config(bus16, bytedir));
      bench.chip->ram_write(0x07FF, 0xBEEF);
      EXPECT_EQ(bench.chip->ram().read(0x07FF), 0xBEEF);
      EXPECT_EQ(bench.chip->ram_read(0x07FF), 0xBEEF);
      bench.chip->reg_write(0x0F, 0x07D0);
      EXPECT_EQ(bench.chip->reg_read(0x0F), 0x07D0);
      EXPECT_EQ(bench.chip->reg_read(0x00), 0x0010);
    }
  }
}

// BUSWIDTH and BYTEDIR are pins: changing them changes the next access.
TEST(BusModes, PinsAreLive) {
  ChipOnBench bench(bus_config(true, false));
  bench.chip->ram_write(0, 0x1234);
  bench.chip->drive(Pin::BYTEDIR, sim::Level::High);
  EXPECT_EQ(bench.chip->bus(ram(0, false)).data, 0x3412);
  bench.chip->drive(Pin::BUSWIDTH, sim::Level::Low);
  EXPECT_EQ(bench.chip->bus(ram(0, false)).data, 0xFF12);
}

// --- byte accesses to registers --------------------------------------------------------

// A byte write touches only its half: on an 8-bit bus, 0x02 in the high byte of 0x01 is
// bit 9 (POLTXD), not SWRST.
TEST(RegisterBytes, ByteWritesActOnTheirHalfOnly) {
  ChipOnBench bench(bus_config(false, false));
  Chip& chip = *bench.chip;
  chip.reg_write(0x01, 0x0000);  // RSTFL cleared
  BusCycle c;
  c.pcsn0 = false;
  c.pcs1 = true;
  c.write = true;
  c.address = 0x0003;  // register 0x01, A0 = 1: high byte
  c.data = 0x0002;
  chip.bus(c);
  EXPECT_EQ(chip.reg_read(0x01) & 0x0203, 0x0200);  // POLTXD set, no reset (RSTFL 0)
  c.address = 0x0002;                               // low byte: SWRST
  chip.bus(c);
  EXPECT_EQ(chip.reg_read(0x01) & 0x0203, 0x0001);  // reset: RSTFL 1, POLTXD 0
}

// Byte write of a W1C register clears only bits of the written half.
TEST(RegisterBytes, WriteOneToClearPerByte) {
  ChipOnBench bench(bus_config(true, false));
  Chip& chip = *bench.chip;
  chip.regs().set_bits(0x04, 0x3FFF, true);
  BusCycle c;
  c.pcsn0 = false;
  c.pcs1 = true;
  c.write = true;
  c.address = 0x0009;  // 0x04, A0 = 1, BHEN = 0: high byte only
  c.bhen = false;
  c.data = 0xFFFF;
  chip.bus(c);
  EXPECT_EQ(chip.reg_read(0x04), 0x00FF);
}

// --- chip selects ----------------------------------------------------------------------

// Table 1: RAM needs MCSN0 = MCSN1 = 0; registers PCSN0 = 0 and PCS1 = 1.
TEST(ChipSelect, DecodesEachCombination) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  chip.ram_write(0, 0x5678);
  for (int bits = 0; bits < 16; ++bits) {
    BusCycle c;
    c.mcsn0 = bits & 1;
    c.mcsn1 = bits & 2;
    c.pcsn0 = bits & 4;
    c.pcs1 = bits & 8;
    c.bhen = false;
    const bool ram_sel = !c.mcsn0 && !c.mcsn1;
    const bool reg_sel = !c.pcsn0 && c.pcs1;
    if (ram_sel && reg_sel) {
      EXPECT_THROW(chip.bus(c), std::invalid_argument);
      continue;
    }
    const BusResult r = chip.bus(c);
    EXPECT_EQ(r.data, ram_sel ? 0x5678 : reg_sel ? 0x0010 : 0xFFFF) << bits;
    EXPECT_EQ(r.target, ram_sel   ? BusTarget::Ram
                        : reg_sel ? BusTarget::Registers
                                  : BusTarget::None);
  }
}

// Nothing selected: the chip drives nothing, D15-0 float to 1 through the internal
// pull-ups (datasheet 3.3) -- the 0xFFFF that facts §5 calls "no chip". Writes vanish.
TEST(ChipSelect, UnselectedReadsAllOnesAndWritesNothing) {
  ChipOnBench bench;
  BusCycle c;
  c.address = 0x0014;
  c.bhen = false;
  EXPECT_EQ(bench.chip->bus(c).data, 0xFFFF);
  EXPECT_EQ(bench.chip->bus(c).driven, 0);
  c.write = true;
  c.data = 0x0001;
  bench.chip->bus(c);
  EXPECT_EQ(bench.chip->reg_read(0x0A), 0);
  EXPECT_EQ(bench.chip->ram_read(0x0A), 0);
}

// --- address ranges --------------------------------------------------------------------

// Delta spec 2.5: the 816's RAM is addressed through A11-A1; higher lines do not reach it.
TEST(Addresses, Sercon816RamWrapsOnA11To1) {
  ChipOnBench bench;
  bench.chip->ram_write(0x0001, 0xAAAA);
  EXPECT_EQ(bench.chip->bus(ram(0x1002, false)).data, 0xAAAA);  // A12 ignored
  EXPECT_EQ(bench.chip->bus(ram(0xF002, false)).data, 0xAAAA);
  bench.chip->ram_write(2047, 0x7FF7);
  EXPECT_EQ(bench.chip->ram_read(2047), 0x7FF7);
  EXPECT_THROW(bench.chip->ram_read(2048), std::out_of_range);
  EXPECT_THROW(bench.chip->ram_write(2048, 0), std::out_of_range);
}

// Delta spec 2.5: the 410B has 1K words; A11 does not reach its RAM.
TEST(Addresses, Sercon410BHasOneKilowordOfRam) {
  ChipOnBench bench(config_410b());
  EXPECT_EQ(bench.chip->ram().size(), 1024);
  bench.chip->ram_write(1023, 0x1023);
  EXPECT_EQ(bench.chip->ram_read(1023), 0x1023);
  EXPECT_THROW(bench.chip->ram_read(1024), std::out_of_range);
  bench.chip->ram_write(0x0003, 0x0303);
  EXPECT_EQ(bench.chip->bus(ram(0x0806, false)).data, 0x0303);  // word 1027 wraps to 3
}

// Datasheet 4.1: "The address is the word address which is input by A6-1."
TEST(Addresses, RegistersWrapOnA6To1) {
  ChipOnBench bench;
  BusCycle c;
  c.pcsn0 = false;
  c.pcs1 = true;
  c.bhen = false;
  c.address = 0x0080;  // A7 set: still word 0
  EXPECT_EQ(bench.chip->bus(c).data, 0x0010);
}

// --- reset and high impedance ----------------------------------------------------------

// RSTN = 0 holds the registers at their reset values (project decision): writes are
// ignored, reads give reset values; the RAM stays accessible.
TEST(BusInReset, RegistersHeldRamAccessible) {
  ChipOnBench bench;
  bench.chip->drive(Pin::RSTN, sim::Level::Low);
  bench.chip->reg_write(0x0A, 0x0003);
  EXPECT_EQ(bench.chip->reg_read(0x0A), 0);
  EXPECT_EQ(bench.chip->reg_read(0x00), 0x0010);
  bench.chip->ram_write(5, 0x0505);
  EXPECT_EQ(bench.chip->ram_read(5), 0x0505);
}

// Table 1: OUTZ = 1 puts all pins into high impedance: D15-0 float (read 0xFFFF) and the
// chip takes no write.
TEST(BusInReset, OutzFloatsTheDataBus) {
  ChipOnBench bench;
  bench.chip->ram_write(5, 0x0505);
  bench.chip->drive(Pin::OUTZ, sim::Level::High);
  EXPECT_EQ(bench.chip->reg_read(0x00), 0xFFFF);
  EXPECT_EQ(bench.chip->ram_read(5), 0xFFFF);
  bench.chip->ram_write(5, 0x0000);
  bench.chip->drive(Pin::OUTZ, sim::Level::Low);
  EXPECT_EQ(bench.chip->ram_read(5), 0x0505);
}

}  // namespace
}  // namespace sercon::chip
