// Board decodings (delta spec 2.5): "Existing SERCON410B systems might have the address
// pin A11 connected to the chip select inputs MCSN1 and PCS1 ... Using the new SERCON816,
// address bit A12 must be used for this. When using the SERCON816 in an existing
// application, the upper range of 1024 words can not be used."
#include "sercon/chip/board.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

TEST(BoardCycle, A11DrivesMcsn1AndPcs1) {
  const BusCycle ram = board_cycle(BoardDecoding::A11, 0x07FE);
  EXPECT_EQ(decode_target(ram), BusTarget::Ram);
  const BusCycle regs = board_cycle(BoardDecoding::A11, 0x0800);
  EXPECT_EQ(decode_target(regs), BusTarget::Registers);
  EXPECT_THROW(board_cycle(BoardDecoding::A11, 0x1000), std::out_of_range);
}

TEST(BoardCycle, A12DrivesMcsn1AndPcs1) {
  EXPECT_EQ(decode_target(board_cycle(BoardDecoding::A12, 0x0FFE)), BusTarget::Ram);
  EXPECT_EQ(decode_target(board_cycle(BoardDecoding::A12, 0x1000)), BusTarget::Registers);
  EXPECT_THROW(board_cycle(BoardDecoding::A12, 0x2000), std::out_of_range);
}

// A 410B on its own board: 1K words of RAM below the registers.
TEST(Board, Sercon410BOnA11Board) {
  ChipOnBench bench(config_410b());
  BoardBus bus(*bench.chip, BoardDecoding::A11);
  EXPECT_EQ(bus.read16(bus.register_offset(0x00)), 0x0002);
  bus.write16(bus.ram_offset(1023), 0x3FF0);
  EXPECT_EQ(bench.chip->ram().read(1023), 0x3FF0);
  EXPECT_THROW(bus.ram_offset(1024), std::out_of_range);
}

// An 816 on an A11 board: RAM words 1024..2047 are unreachable from the bus.
TEST(Board, Sercon816OnA11BoardReachesOnlyTheLowerKiloword) {
  ChipOnBench bench;
  BoardBus bus(*bench.chip, BoardDecoding::A11);
  EXPECT_EQ(bus.read16(bus.register_offset(0x00)), 0x0010);
  bench.chip->ram().write(1024, 0x0400);
  bench.chip->ram().write(0, 0x0000);
  for (std::uint16_t offset = 0; offset < 0x0800; offset = static_cast<std::uint16_t>(offset + 2)) {
    ASSERT_NE(bus.read16(offset), 0x0400) << offset;  // word 1024 is never seen
  }
  // Every offset with A11 = 1 reaches the registers, not RAM words 1024..
  bus.write16(0x0800 + 2 * 0x0A, 0x0003);
  EXPECT_EQ(bench.chip->reg_read(0x0A), 0x0003);
  EXPECT_EQ(bench.chip->ram().read(1024 + 0x0A), 0);
}

// An 816 on its own (A12) board reaches all 2K words.
TEST(Board, Sercon816OnA12BoardReachesAllRam) {
  ChipOnBench bench;
  BoardBus bus(*bench.chip, BoardDecoding::A12);
  bus.write16(bus.ram_offset(2047), 0x7FF0);
  bus.write16(bus.ram_offset(1024), 0x4000);
  EXPECT_EQ(bench.chip->ram().read(2047), 0x7FF0);
  EXPECT_EQ(bench.chip->ram().read(1024), 0x4000);
  EXPECT_EQ(bus.read16(bus.register_offset(0x00)), 0x0010);
  bus.write16(bus.register_offset(0x2A), 0x1234);  // TWDOG
  EXPECT_EQ(bench.chip->reg_read(0x2A), 0x1234);
}

// A 410B in an 816 (A12) board: its RAM repeats (A11 not connected to it), registers work.
TEST(Board, Sercon410BOnA12BoardSeesItsRamTwice) {
  ChipOnBench bench(config_410b());
  BoardBus bus(*bench.chip, BoardDecoding::A12);
  bus.write16(bus.ram_offset(5), 0x0505);
  EXPECT_EQ(bus.read16(bus.ram_offset(1024 + 5)), 0x0505);
  EXPECT_EQ(bus.read16(bus.register_offset(0x00)), 0x0002);
}

// On an 8-bit board every word becomes two byte cycles.
TEST(Board, EightBitBoard) {
  ChipConfig config;
  config.buswidth = false;
  config.bytedir = true;
  ChipOnBench bench(config);
  BoardBus bus(*bench.chip, BoardDecoding::A12);
  bus.write16(bus.ram_offset(9), 0xA1B2);
  EXPECT_EQ(bench.chip->ram().read(9), 0xA1B2);
  EXPECT_EQ(bus.read16(bus.ram_offset(9)), 0xA1B2);
}

}  // namespace
}  // namespace sercon::chip
