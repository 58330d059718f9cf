// Access rules for every register and field, generated from the register table (the
// single source of truth, register_map.cpp). Datasheet 4.1: "If control registers are
// read with bits that are not used, these bits are set to 0"; status bits (R) ignore
// writes; control bits (RW) are stored; W1C status bits clear on writing 1.
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "chip_fixture.hpp"
#include "sercon/chip/register_file.hpp"
#include "sercon/chip/register_map.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

ChipConfig config_of(Variant v) { return v == Variant::Sercon816 ? ChipConfig{} : config_410b(); }

bool present(const BitField& f, Variant v) {
  return f.variants == Variants::Both ||
         (f.variants == Variants::Only816) == (v == Variant::Sercon816);
}

class EveryRegister : public ::testing::TestWithParam<std::tuple<Variant, std::uint8_t>> {
 protected:
  Variant variant() const { return std::get<0>(GetParam()); }
  std::uint8_t address() const { return std::get<1>(GetParam()); }
  RegisterMasks masks() const { return register_masks(address(), variant()); }
};

// --- the register file on its own: exactly the table's rules ---------------------------

TEST_P(EveryRegister, FileResetsToTheTableValue) {
  RegisterFile file(variant());
  EXPECT_EQ(file.value(address()), masks().reset);
  EXPECT_EQ(file.bus_read(address()), masks().reset & masks().readable);
}

TEST_P(EveryRegister, FileUnusedBitsReadZero) {
  RegisterFile file(variant());
  file.set_bits(address(), 0xFFFF, true);
  EXPECT_EQ(file.bus_read(address()) & ~masks().readable, 0);
  file.bus_write(address(), 0xFFFF);
  EXPECT_EQ(file.bus_read(address()) & ~masks().readable, 0);
}

TEST_P(EveryRegister, FileStatusBitsIgnoreWrites) {
  const RegisterMasks m = masks();
  const auto status = static_cast<std::uint16_t>(m.readable & ~m.writable & ~m.clearable);
  RegisterFile file(variant());
  for (std::uint16_t pattern : {std::uint16_t{0x0000}, std::uint16_t{0xFFFF}}) {
    file.set_bits(address(), status, pattern == 0);  // opposite of what is written
    const std::uint16_t before = file.value(address());
    file.bus_write(address(), pattern);
    EXPECT_EQ(file.value(address()) & status, before & status);
  }
}

TEST_P(EveryRegister, FileControlBitsAreStored) {
  const std::uint16_t rw = masks().writable;
  RegisterFile file(variant());
  for (unsigned pattern : {0xA5A5u, 0x5A5Au, 0xFFFFu, 0x0000u}) {
    file.bus_write(address(), static_cast<std::uint16_t>(pattern));
    EXPECT_EQ(file.bus_read(address()) & rw, pattern & rw);
  }
}

TEST_P(EveryRegister, FileWriteOneClearsOnlyTheWrittenStatusBits) {
  const std::uint16_t w1c = masks().clearable;
  RegisterFile file(variant());
  file.set_bits(address(), w1c, true);
  file.bus_write(address(), 0x0000);
  EXPECT_EQ(file.value(address()) & w1c, w1c);  // writing 0 keeps them
  for (unsigned bit = 0; bit < 16; ++bit) {
    const auto m = static_cast<std::uint16_t>(1u << bit);
    if (!(w1c & m)) continue;
    file.set_bits(address(), w1c, true);
    file.bus_write(address(), m);
    EXPECT_EQ(file.value(address()) & w1c, w1c & ~m) << "bit " << bit;
  }
}

TEST_P(EveryRegister, FileByteWritesTouchOnlyTheirHalf) {
  const std::uint16_t rw = masks().writable;
  RegisterFile file(variant());
  file.bus_write(address(), 0x0000);
  file.bus_write(address(), 0xFFFF, 0x00FF);
  EXPECT_EQ(file.value(address()) & rw, rw & 0x00FF);
  file.bus_write(address(), 0xFFFF, 0xFF00);
  EXPECT_EQ(file.value(address()) & rw, rw);
}

// --- the same rules through the chip's bus, field by field --------------------------

TEST_P(EveryRegister, ChipReadsUnusedBitsAsZero) {
  ChipOnBench bench(config_of(variant()));
  for (unsigned pattern : {0xFFFFu, 0x0000u}) {
    bench.chip->reg_write(address(), static_cast<std::uint16_t>(pattern));
    EXPECT_EQ(bench.chip->reg_read(address()) & ~masks().readable, 0);
  }
}

TEST_P(EveryRegister, ChipFieldsObeyTheirAccess) {
  ChipOnBench bench(config_of(variant()));
  Chip& chip = *bench.chip;
  for (const BitField& f : register_info(address()).fields) {
    if (!present(f, variant())) continue;
    SCOPED_TRACE(std::string(f.name));
    const std::uint16_t m = f.mask();
    switch (f.access) {
      case Access::R: {  // writing the complement changes nothing
        const std::uint16_t before = chip.reg_read(address());
        chip.reg_write(address(), static_cast<std::uint16_t>(~before & m));
        EXPECT_EQ(chip.reg_read(address()) & m, before & m);
        break;
      }
      case Access::RW:
        for (unsigned pattern : {0x5555u, 0xAAAAu, 0x0000u}) {
          chip.reg_write(address(), static_cast<std::uint16_t>(pattern & m));
          EXPECT_EQ(chip.reg_read(address()) & m, pattern & m);
        }
        break;
      case Access::W1C:
        chip.regs().set_bits(address(), m, true);
        EXPECT_EQ(chip.reg_read(address()) & m, m);
        chip.reg_write(address(), 0);
        EXPECT_EQ(chip.reg_read(address()) & m, m);
        chip.reg_write(address(), m);
        EXPECT_EQ(chip.reg_read(address()) & m, 0);
        break;
      case Access::W:  // acts on 1 and reads as a status: nothing to read back generically
        break;
    }
  }
}

std::string name_of(const ::testing::TestParamInfo<std::tuple<Variant, std::uint8_t>>& info) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::uint8_t a = std::get<1>(info.param);
  std::string name(to_string(std::get<0>(info.param)));
  name += "_0x";
  name += kHex[unsigned{a} >> 4];
  name += kHex[unsigned{a} & 0xFu];
  for (char c : register_info(a).name) name += c == '_' ? 'x' : c;
  return name;
}

INSTANTIATE_TEST_SUITE_P(Table, EveryRegister,
                         ::testing::Combine(::testing::Values(Variant::Sercon816,
                                                              Variant::Sercon410B),
                                            ::testing::Range<std::uint8_t>(0, kRegisterCount)),
                         name_of);

// --- addresses past the table ----------------------------------------------------------

// A6-1 reach word addresses up to 0x3F; 0x2B..0x3F hold no register: read 0, writes
// ignored (project decision, docs/chip.md).
TEST(RegisterAddresses, WordsBeyondTheTableReadZero) {
  ChipOnBench bench;
  for (std::uint16_t a = kRegisterCount; a <= 0x3F; ++a) {
    bench.chip->reg_write(a, 0xFFFF);
    EXPECT_EQ(bench.chip->reg_read(a), 0) << a;
  }
  EXPECT_THROW(bench.chip->reg_read(0x40), std::out_of_range);
  EXPECT_THROW(bench.chip->reg_write(0x40, 0), std::out_of_range);
}

// Delta spec 2.11.2 lists 0x28..0x2A as "SERCON816 NEW Control Registers": the 410B has
// none of them, so they read 0 there.
TEST(RegisterAddresses, Sercon410BHasNoWatchdogRegisters) {
  ChipOnBench bench(config_410b());
  for (std::uint16_t a = 0x28; a <= 0x2A; ++a) {
    bench.chip->reg_write(a, 0xFFFF);
    EXPECT_EQ(bench.chip->reg_read(a), 0) << a;
  }
}

}  // namespace
}  // namespace sercon::chip
