// The DMA port on its pins (datasheet Table 1 DMAREQR / DMAACKRN / DMAREQT / DMAACKTN,
// 3.5.1 t_MCLD; docs/chip.md "Resets"; docs/telegram-processing.md "DMA"): a chip on the
// timing bench, no ring; the test plays the DMA controller. Transfers through telegrams
// are in telegram_dma_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>

#include "sercon/chip/dma_port.hpp"
#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

constexpr Time kStrobe = 50'000;  // 50 ns
// DMACTRL (0x0C): DMARXEN bit 0, DMATXEN bit 1 (docs/registers.md).
constexpr std::uint16_t kDmaRxEn = 0x0001;
constexpr std::uint16_t kDmaTxEn = 0x0002;

struct DmaPins : TimingBench {
  void run_for(Time t) { run_to(now() + t); }
  // One DMA controller write cycle on the pins (Intel bus: WRN strobe, DMAACKTN = 0).
  void dma_write(std::uint16_t word) {
    for (unsigned bit = 0; bit < 16; ++bit) {
      chip.drive(data_pin(bit), sim::level_of(((unsigned{word} >> bit) & 1u) != 0));
    }
    chip.drive(Pin::DMAACKTN, Level::Low);
    chip.drive(Pin::WRN, Level::Low);
    run_for(kStrobe);
    chip.drive(Pin::WRN, Level::High);
    chip.drive(Pin::DMAACKTN, Level::High);
    for (unsigned bit = 0; bit < 16; ++bit) chip.drive(data_pin(bit), Level::HighZ);
    run_for(kStrobe);
  }
  // One DMA controller read cycle on the pins (Intel bus: RDN strobe, DMAACKRN = 0).
  void dma_read() {
    chip.drive(Pin::DMAACKRN, Level::Low);
    chip.drive(Pin::RDN, Level::Low);
    run_for(kStrobe);
    chip.drive(Pin::RDN, Level::High);
    chip.drive(Pin::DMAACKRN, Level::High);
    run_for(kStrobe);
  }
};

// docs/chip.md "Resets": while RSTN = 0 or OUTZ = 1 "the registers are held: writes are
// ignored and reads give reset values", and every reset loads the reset values (INTSTAT
// 0x0000, docs/registers.md). A DMA controller that is still cycling while the host holds
// the chip in reset must not leave a latched INT_DMAERR behind: the DMA port ignores
// acknowledged strobes in reset (its FIFOs are reset and disabled, and nothing may latch).
TEST(DmaPort, StrobesWhileHeldInResetLatchNoInterrupt) {
  for (const Pin reset_pin : {Pin::RSTN, Pin::OUTZ}) {
    // 0: no strobe (the control case: the reset alone leaves INTSTAT clear), 1: a write,
    // 2: a read.
    for (const int strobe : {0, 1, 2}) {
      DmaPins b;
      const Level active = reset_pin == Pin::RSTN ? Level::Low : Level::High;
      const Level inactive = reset_pin == Pin::RSTN ? Level::High : Level::Low;
      b.run_to(kMicrosecond);
      b.chip.drive(reset_pin, active);
      b.run_for(kMicrosecond);
      if (strobe == 1) b.dma_write(0x1234);
      if (strobe == 2) b.dma_read();
      b.chip.drive(reset_pin, inactive);
      b.run_for(kMicrosecond);
      EXPECT_EQ(b.chip.reg_read(kIntStat) & kIntDmaerr, 0)
          << (reset_pin == Pin::RSTN ? "RSTN = 0" : "OUTZ = 1") << ", strobe " << strobe;
    }
  }
}

// The same for the word API's whole DMA cycles (docs/chip.md "Resets": "acknowledge_read()
// gives 0xFFFF"): in reset a read finds nothing to answer it (the floating bus, 0xFFFF) and
// a write goes nowhere; neither counts or latches anything. The reset also disables both
// FIFOs (DMACTRL 0), so 0xFFFF and the count hold either way: INT_DMAERR is what tells a
// held port from one that answers (an underrun / overrun of a disabled FIFO would latch it,
// docs/telegram-processing.md §9; dropping either in-reset guard fails here).
TEST(DmaPort, WholeCyclesWhileHeldInResetDoNothing) {
  DmaPins b;
  DmaPort& port = *b.chip.unit<DmaPort>();
  b.chip.drive(Pin::RSTN, Level::Low);
  port.acknowledge_write(0x1234);
  EXPECT_EQ(port.acknowledge_read(), 0xFFFF);
  EXPECT_EQ(port.transmit_count(), 0u);
  b.chip.drive(Pin::RSTN, Level::High);
  EXPECT_EQ(b.chip.reg_read(kIntStat) & kIntDmaerr, 0);
}

// The same defect the pin bus had: a DMA read in progress when RSTN falls must not keep
// driving the FIFO word (docs/chip.md "Resets": every reset sets D15-0 HighZ).
TEST(DmaPort, RstnDuringAReadReleasesD15To0) {
  DmaPins b;
  b.chip.reg_write(kDmaCtrl, kDmaRxEn);
  const std::uint16_t word = 0x1234;
  b.chip.unit<DmaPort>()->receive(std::span(&word, 1));
  b.chip.drive(Pin::DMAACKRN, Level::Low);
  b.chip.drive(Pin::RDN, Level::Low);
  ASSERT_TRUE(b.chip.drives(Pin::D2));  // bit 2 of 0x1234
  b.chip.drive(Pin::RSTN, Level::Low);
  for (unsigned bit = 0; bit < 16; ++bit) EXPECT_FALSE(b.chip.drives(data_pin(bit))) << bit;
  b.chip.drive(Pin::RDN, Level::High);
  b.chip.drive(Pin::DMAACKRN, Level::High);
  b.chip.drive(Pin::RSTN, Level::High);
}

// Datasheet 3.5.1, t_MCLD: "Output delay rising edge MCLK to DMAREQR/T, CON_CLK, DIV_CLK",
// max 20 ns. DMAREQT is an MCLK-clocked output: every change that is not the strobe-driven
// fall of t_PRQ (3.5.6) must come at most 20 ns after a rising MCLK edge (the model adds no
// output delay, so at the edge itself). Enabling the transmit FIFO (DMACTRL.DMATXEN, a
// project register) by a bus write 25 ns after an MCLK edge (32 MHz: 31.25 ns period) must
// raise DMAREQT at the next edge, not at the write instant.
TEST(DmaPort, DmareqtRisesWithinTmcldOfAnMclkEdge) {
  DmaPins b;
  PinLog reqt(b.bench.scheduler, b.pin(Pin::DMAREQT));
  const Time t_mcld = 20'000;
  const Time written = 320 * b.mclk() + 25'000;  // 25 ns after MCLK edge 320
  b.write_at(written, kDmaCtrl, kDmaTxEn);
  b.run_for(kMicrosecond);
  ASSERT_EQ(reqt.times_of(Level::High).size(), 1u);
  const Time rise = reqt.times_of(Level::High).front();
  const Time since_edge = rise % b.mclk();  // MCLK edges at k * period (docs/timing.md)
  EXPECT_GE(rise, written);
  EXPECT_LE(since_edge, t_mcld) << "DMAREQT rose at " << rise << " ps, " << since_edge
                                << " ps after the last rising MCLK edge";
}

// Decision (docs/telegram-processing.md "DMA"): a DMACTRL write acts on the FIFOs and on
// RXCNT / TXCNT at once, so a host reading the register right after its write sees the
// FIFO state it made; DMAREQR/T, MCLK-clocked outputs, follow that state at the next MCLK
// edge, a rise (enable) as a drop (disable, which also empties the FIFO).
TEST(DmaPort, ControlWritesActAtOnceAndTheRequestsFollowAtTheNextMclkEdge) {
  DmaPins b;
  const Time written = 320 * b.mclk() + 25'000;
  const Time edge = 321 * b.mclk();
  b.write_at(written, kDmaCtrl, kDmaTxEn);
  EXPECT_EQ(b.chip.reg_read(kDmaCtrl), kDmaTxEn);  // enabled, TXCNT = 0
  EXPECT_EQ(b.pin(Pin::DMAREQT).level(), Level::Low);
  b.run_to(edge - 1);
  EXPECT_EQ(b.pin(Pin::DMAREQT).level(), Level::Low);
  b.run_to(edge);
  EXPECT_EQ(b.pin(Pin::DMAREQT).level(), Level::High);
  b.dma_write(0x1234);
  EXPECT_EQ(b.chip.reg_read(kDmaCtrl), kDmaTxEn | 1u << 2);  // TXCNT = 1
  const Time disabled = b.now() + 10'000;
  ASSERT_NE(disabled % b.mclk(), 0);
  b.write_at(disabled, kDmaCtrl, 0);
  EXPECT_EQ(b.chip.reg_read(kDmaCtrl), 0);  // emptied: TXCNT = 0
  EXPECT_EQ(b.pin(Pin::DMAREQT).level(), Level::High);
  b.run_to(edge_at_or_after(disabled, b.mclk()));
  EXPECT_EQ(b.pin(Pin::DMAREQT).level(), Level::Low);
}

// Datasheet 3.5.6 t_AHD: DMAACKNT may go inactive at the very instant WRN rises (hold
// 0 ns). A DMA controller modelled as one scheduler event that ends the strobe and drops
// the acknowledge together still writes its word into the transmit FIFO, as the same pin
// changes made outside an event do: the chip reacts to each pin change at once
// (sim/signal.hpp: a model's reactions run depth first; only watchers wait for the step).
TEST(DmaPort, WriteEndTakesTheAcknowledgeAsItWasAtTheStrobeEnd) {
  DmaPins b;
  b.chip.reg_write(0x0C, kDmaTxEn);
  for (unsigned bit = 0; bit < 16; ++bit) {
    b.chip.drive(data_pin(bit), sim::level_of(((0x1234u >> bit) & 1u) != 0));
  }
  b.chip.drive(Pin::DMAACKTN, Level::Low);
  b.chip.drive(Pin::WRN, Level::Low);
  const Time end = b.now() + kStrobe;
  b.bench.scheduler.at(end, [&b] {
    b.chip.drive(Pin::WRN, Level::High);
    b.chip.drive(Pin::DMAACKTN, Level::High);
    for (unsigned bit = 0; bit < 16; ++bit) b.chip.drive(data_pin(bit), Level::HighZ);
  });
  b.run_for(2 * kStrobe);
  auto& port = *b.chip.unit<DmaPort>();
  ASSERT_EQ(port.transmit_count(), 1u);
  std::uint16_t word = 0;
  port.transmit(std::span<std::uint16_t>(&word, 1));
  EXPECT_EQ(word, 0x1234);  // D15-0 as they were when WRN rose, not floating
}

}  // namespace
}  // namespace sercon::chip
