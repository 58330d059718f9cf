#include "phase_up.hpp"

#include <array>
#include <cstdint>
#include <vector>

#include "cycle_writer.hpp"

namespace sercon::sample {
namespace {

constexpr unsigned kBitsPerUs = 4;  // 4 Mbit/s
constexpr std::size_t kLeadInBits = 32;
constexpr std::size_t kTailBits = 64;
constexpr unsigned kDrives = 4;

// CP0..CP2: the telegram list times of a real master (sercos-facts §5: AT received at
// 100 us, MDT sent at 600 us), in a cycle halved from its 2 ms.
constexpr unsigned kSlowCycleUs = 1000;
constexpr unsigned kSlowAtUs = 100;
constexpr unsigned kSlowMdtUs = 600;

// CP3/CP4: the 2 Mbit/s ring of sercos-facts §4 (2000 us cycle, T1 92 + 244 k, T2 1782,
// 8-byte records) scaled to 4 Mbit/s and a 500 us cycle.
constexpr unsigned kFastCycleUs = 500;                             // IDN 1/2
constexpr std::array<unsigned, kDrives> kT1Us{46, 108, 170, 232};  // IDN 6 per drive
constexpr unsigned kT2Us = 380;                                    // IDN 89

using Bytes = std::vector<std::uint8_t>;

void put16(Bytes& out, std::uint16_t v) {  // words little-endian (sercos-facts §2)
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

void put32(Bytes& out, std::uint32_t v) {  // 4-byte values low word first (sercos-facts §3)
  put16(out, static_cast<std::uint16_t>(v & 0xFFFF));
  put16(out, static_cast<std::uint16_t>(v >> 16));
}

Bytes words(std::uint16_t first, std::uint16_t second) {
  Bytes out;
  put16(out, first);
  put16(out, second);
  return out;
}

void cp0(CycleWriter& w) {
  for (int i = 0; i < 10; ++i) w.begin_cycle(kSlowCycleUs, 0);  // ring check: MSTs only
}

// Address scan: each drive gets control word 0x0001 / info 0 for two cycles and answers
// the first of them with its address and status bit 0 set.
void cp1(CycleWriter& w) {
  for (std::uint8_t drive = 1; drive <= kDrives; ++drive) {
    for (int repeat = 0; repeat < 2; ++repeat) {
      w.begin_cycle(kSlowCycleUs, 1);
      if (repeat == 1) w.send(kSlowAtUs, drive, words(0x0001, 0));
      w.send(kSlowMdtUs, drive, words(0x0001, 0));
    }
  }
}

// Service channel to drive 1 (sercos-facts §3): read IDN 3 (t1min), then write IDN 1
// (cycle time). The AT of each cycle answers the MDT step of the cycle before.
void cp2(CycleWriter& w) {
  struct Step {
    std::uint16_t control;
    std::uint16_t info;
    std::uint16_t answer;  // AT service info
  };
  constexpr std::array<Step, 8> kSteps{{
      {0x0F, 0x0003, 0x0000},        // open IDN 3
      {0x18, 0x0003, 0x0001},        // attribute, first word (conversion factor 1)
      {0x1D, 0x0003, 0x0011},        // attribute, last word: 2 bytes, unsigned
      {0x3C, 0x0003, 12},            // operation data with END: t1min = 12 us
      {0x07, 0x0003, 0x0000},        // close
      {0x0E, 0x0001, 0x0000},        // open IDN 1
      {0x3F, kFastCycleUs, 0x0000},  // write operation data with END: tNcyc
      {0x06, 0x0001, 0x0000},        // close
  }};
  for (std::size_t cycle = 0; cycle <= kSteps.size(); ++cycle) {
    w.begin_cycle(kSlowCycleUs, 2);
    if (cycle > 0) {
      const Step& done = kSteps[cycle - 1];
      w.send(kSlowAtUs, 1, words(done.control & 0x0001U, done.answer));  // AHS = MHS
    }
    if (cycle < kSteps.size())
      w.send(kSlowMdtUs, 1, words(kSteps[cycle].control, kSteps[cycle].info));
  }
}

std::uint32_t position_command(unsigned drive, unsigned cycle) {
  return 0x10000U * drive + 100U * cycle;
}

// One CP3/CP4 cycle: four 8-byte ATs (status, service info, position feedback) and the
// broadcast MDT of four 8-byte records (control word, service info, position command).
void fast_cycle(CycleWriter& w, std::uint8_t phase, unsigned cycle, int corrupt_drive) {
  const bool operating = phase == 4;
  w.begin_cycle(kFastCycleUs, phase);
  for (unsigned drive = 1; drive <= kDrives; ++drive) {
    Bytes at;
    put16(at, operating ? 0xC000 : 0x4000);  // IDN 135: operating / logic ready
    put16(at, 0);
    put32(at, operating && cycle > 0 ? position_command(drive, cycle - 1) : 0x10000U * drive);
    const auto address = static_cast<std::uint8_t>(drive);
    if (static_cast<int>(drive) == corrupt_drive) {
      w.send_corrupted(kT1Us[drive - 1], address, at);
    } else {
      w.send(kT1Us[drive - 1], address, at);
    }
  }
  Bytes mdt;  // records at IDN 9 = 1, 9, 17, 25; IDN 10 = 32
  for (unsigned drive = 1; drive <= kDrives; ++drive) {
    put16(mdt, operating ? 0xE000 : 0x0000);  // IDN 134: drive on, enable, halt/restart
    put16(mdt, 0);
    put32(mdt, operating ? position_command(drive, cycle) : 0x10000U * drive);
  }
  w.send(kT2Us, 255, mdt);
}

}  // namespace

wire::LineBits phase_up_4drives() {
  CycleWriter w(kBitsPerUs, kLeadInBits);
  cp0(w);
  cp1(w);
  cp2(w);
  for (unsigned cycle = 0; cycle < 8; ++cycle) fast_cycle(w, 3, cycle, -1);
  for (unsigned cycle = 0; cycle < 16; ++cycle) fast_cycle(w, 4, cycle, cycle == 10 ? 3 : -1);
  return w.finish(kTailBits);
}

wire::LineBits cp4_excerpt() {
  CycleWriter w(kBitsPerUs, kLeadInBits);
  fast_cycle(w, 4, 20, -1);
  fast_cycle(w, 4, 21, -1);
  return w.finish(kTailBits);
}

}  // namespace sercon::sample
