// DMA transfer of telegram data (datasheet 4.2.1 DMA bit; Table 1 DMAREQR / DMAACKRN /
// DMAREQT / DMAACKTN; docs/telegram-processing.md, "DMA"): a master on a loop sends and
// receives its own telegram through the FIFOs, and the test plays the DMA controller on
// the pins.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "sercon/chip/dma_port.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;
using sim::Level;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 100;
constexpr Time kStrobe = 50'000;  // 50 ns
constexpr std::uint16_t kRxHeader = 0x050;

// DMACTRL (0x0C): DMARXEN bit 0, DMATXEN bit 1, TXCNT bits 2..6, RXCNT bits 8..12.
constexpr std::uint16_t kDmaRxEn = 0x0001;
constexpr std::uint16_t kDmaTxEn = 0x0002;
unsigned txcnt(std::uint16_t dmactrl) { return (dmactrl >> 2) & 0x1Fu; }
unsigned rxcnt(std::uint16_t dmactrl) { return (dmactrl >> 8) & 0x1Fu; }

class Dma : public ::testing::Test {
 protected:
  explicit Dma(ChipConfig config = {}) : ring(1, kFibre, config) {
    chip().pin(Pin::DMAREQR).watch([this](Level l) { reqr.emplace_back(now(), l); });
    chip().pin(Pin::DMAREQT).watch([this](Level l) { reqt.emplace_back(now(), l); });
  }

  // The list: transmit header `tx` (3 words from RAM, or a 3-word DMA container), receive
  // header `rx` (3 words), end marker. The RAM container at 0x044 holds `data`.
  void start(std::uint16_t tx, std::uint16_t rx,
             std::array<std::uint16_t, 3> data = {0x1111, 0x2222, 0x3333}) {
    t = timing_16mbit();
    Chip& m = chip();
    program_master(m, t, kTscyc, 4);
    words(m, 0x000, {0x060, 0x040});
    transmit_header(m, 0x040, tx, 20, 3, kRxHeader);
    words(m, 0x044, {0x8003, data[0], data[1], data[2]});
    receive_header(m, kRxHeader, rx, 0, 3, 0x060);
    words(m, 0x055, {0x8003, 0, 0, 0, 0});
    end_marker(m, 0x060, 90);
    enable_transmission(m);
    ring.run_for(555'555);
    first = ceil_to(now(), t.mclk());
    start_master(m);
  }

  Chip& chip() { return ring.chip(0); }
  Time now() const { return ring.scheduler.now(); }
  bool high(Pin p) { return chip().pin(p).level() == Level::High; }

  // One DMA controller cycle on the pins (Intel bus: RDN / WRN strobes), `kStrobe` long.
  std::uint16_t dma_read() {
    chip().drive(Pin::DMAACKRN, Level::Low);
    chip().drive(Pin::RDN, Level::Low);
    std::uint16_t word = 0;
    for (unsigned bit = 0; bit < 16; ++bit) {
      if (chip().input_high(data_pin(bit))) word = static_cast<std::uint16_t>(word | 1u << bit);
    }
    ring.run_for(kStrobe);
    chip().drive(Pin::RDN, Level::High);
    chip().drive(Pin::DMAACKRN, Level::High);
    ring.run_for(kStrobe);
    return word;
  }
  void dma_write(std::uint16_t word) {
    begin_dma_write(word);
    end_dma_write();
  }
  void begin_dma_write(std::uint16_t word) {
    for (unsigned bit = 0; bit < 16; ++bit) {
      chip().drive(data_pin(bit), sim::level_of(((unsigned{word} >> bit) & 1u) != 0));
    }
    chip().drive(Pin::DMAACKTN, Level::Low);
    chip().drive(Pin::WRN, Level::Low);
    ring.run_for(kStrobe);
  }
  void end_dma_write() {
    chip().drive(Pin::WRN, Level::High);
    chip().drive(Pin::DMAACKTN, Level::High);
    for (unsigned bit = 0; bit < 16; ++bit) chip().drive(data_pin(bit), Level::HighZ);
    ring.run_for(kStrobe);
  }
  // The detection of the cycle-0 telegram (3 data words) back at the receiver.
  Time detected(const std::vector<std::uint8_t>& data) const {
    const Time start = on_bit_grid(cycle_time(first, 20, t), t);
    return detection(start + kFibre + static_cast<Time>(line_bits(5, data)) * t.bit, t);
  }
  std::vector<std::uint8_t> list_data() const {
    for (const Seen& s : ring.fibres[0]->seen) {
      if (s.data.size() != 1) return s.data;
    }
    return {};
  }

  Ring ring;
  Timing t;
  Time first = 0;
  std::vector<std::pair<Time, Level>> reqr, reqt;
};

const std::vector<std::uint8_t> kData{0x11, 0x11, 0x22, 0x22, 0x33, 0x33};

TEST_F(Dma, ReceivedWordsEnterTheFifoAtDetection) {
  // Table 1 DMAREQR: "becomes active if data from the receive FIFO can be read".
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905);  // receive ACHK + DMA, address 5
  const Time at = detected(kData);
  ring.scheduler.run_until(at - 1);
  EXPECT_FALSE(high(Pin::DMAREQR));
  ring.scheduler.run_until(at);
  EXPECT_TRUE(high(Pin::DMAREQR));
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 3u);
  // Datasheet 4.2.1 VAL for DMA = 1: "telegram data is ... valid (VAL = 1)".
  EXPECT_EQ(chip().ram_read(kRxHeader), 0x0905 | 0x0400);
  // The RAM after the control words is not written: DMA containers have no buffer.
  EXPECT_EQ(chip().ram_read(0x057), 0);
}

TEST_F(Dma, DmareqrDropsAtTheBeginningOfTheReadOfTheLastWord) {
  // Table 1 DMAREQR: "At the beginning of the read operation of the last word of the
  // receive FIFO, DMAREQR becomes inactive."
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905);
  ring.scheduler.run_until(detected(kData));
  EXPECT_EQ(dma_read(), 0x1111);
  EXPECT_EQ(dma_read(), 0x2222);
  EXPECT_TRUE(high(Pin::DMAREQR));
  const Time last_read = now();
  EXPECT_EQ(dma_read(), 0x3333);
  ASSERT_FALSE(reqr.empty());
  EXPECT_EQ(reqr.back(), std::make_pair(last_read, Level::Low));
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 0u);
}

TEST_F(Dma, AcknowledgedReadIgnoresAddressAndChipSelects) {
  // Table 1 DMAACKRN: "when DMAACKRN is 0, the receive FIFO is read, independent of the
  // levels on A6-1 and the chip select signals".
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905);
  ring.scheduler.run_until(detected(kData));
  chip().drive(Pin::PCSN0, Level::Low);  // register 0 (VERSION) selected
  chip().drive(Pin::PCS1, Level::High);
  EXPECT_EQ(dma_read(), 0x1111);
  chip().drive(Pin::PCSN0, Level::High);
  chip().drive(Pin::PCS1, Level::Low);
  chip().drive(Pin::MCSN0, Level::Low);  // RAM word 0 selected
  chip().drive(Pin::MCSN1, Level::Low);
  EXPECT_EQ(dma_read(), 0x2222);
  chip().drive(Pin::MCSN0, Level::High);
  chip().drive(Pin::MCSN1, Level::High);
  EXPECT_EQ(dma_read(), 0x3333);
}

TEST_F(Dma, AcknowledgedWritesFeedTheTransmitTelegram) {
  // Table 1 DMAREQT: "active when data can be written to the transmit FIFO"; DMAACKTN:
  // "the transmit FIFO is written to ... independent of the levels on A6-1 and the chip
  // select signals". Datasheet 4.2.2: with DMA = 1 the container holds only control words.
  chip().reg_write(kDmaCtrl, kDmaTxEn);
  EXPECT_TRUE(high(Pin::DMAREQT));
  chip().ram_write(0x000, 0x5A5A);       // marker: start() below rewrites word 0
  chip().drive(Pin::MCSN0, Level::Low);  // RAM word 0 selected: must stay untouched
  chip().drive(Pin::MCSN1, Level::Low);
  dma_write(0xAAAA);
  dma_write(0xBBBB);
  dma_write(0xCCCC);
  chip().drive(Pin::MCSN0, Level::High);
  chip().drive(Pin::MCSN1, Level::High);
  EXPECT_EQ(chip().ram_read(0x000), 0x5A5A);  // the DMA writes went to the FIFO only
  EXPECT_EQ(txcnt(chip().reg_read(kDmaCtrl)), 3u);
  start(0x5105, 0x0805);  // transmit with DMA = 1
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_EQ(list_data(), (std::vector<std::uint8_t>{0xAA, 0xAA, 0xBB, 0xBB, 0xCC, 0xCC}));
  EXPECT_EQ(chip().ram_read(0x000), 0x060);
  EXPECT_EQ(txcnt(chip().reg_read(kDmaCtrl)), 0u);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntDmaerr);
}

TEST_F(Dma, DmareqtDropsAtTheBeginningOfTheWriteThatFillsTheFifo) {
  // Table 1 DMAREQT: "becomes inactive again at the beginning of the last write access".
  // Depth: 16 words (docs/telegram-processing.md).
  chip().reg_write(kDmaCtrl, kDmaTxEn);
  for (std::uint16_t i = 0; i < DmaPort::kDepth - 1; ++i) dma_write(i);
  EXPECT_TRUE(high(Pin::DMAREQT));
  const Time begins = now();
  begin_dma_write(0x00FF);
  EXPECT_FALSE(high(Pin::DMAREQT));
  EXPECT_EQ(reqt.back(), std::make_pair(begins, Level::Low));
  end_dma_write();
  EXPECT_EQ(txcnt(chip().reg_read(kDmaCtrl)), 16u);
  dma_write(0x0100);  // one too many: overrun
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntDmaerr);
  EXPECT_EQ(txcnt(chip().reg_read(kDmaCtrl)), 16u);
}

TEST_F(Dma, EmptyTransmitFifoIsAnUnderrun) {
  chip().reg_write(kDmaCtrl, kDmaTxEn);
  dma_write(0xAAAA);
  start(0x5105, 0x0805);
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntDmaerr);
  EXPECT_EQ(list_data(), (std::vector<std::uint8_t>{0xAA, 0xAA, 0, 0, 0, 0}));
}

TEST_F(Dma, FullReceiveFifoIsAnOverrun) {
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905);
  ring.run_for(5 * kTscyc * sim::kMicrosecond);  // 15 words: they fit
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntDmaerr);
  ring.run_for(kTscyc * sim::kMicrosecond);  // 3 more: one fits
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntDmaerr);
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 16u);
}

TEST_F(Dma, DisabledReceiveFifoTakesNothing) {
  start(0x5005, 0x0905);  // DMARXEN = 0
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntDmaerr);
  EXPECT_FALSE(high(Pin::DMAREQR));
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 0u);
}

TEST_F(Dma, ClearingTheEnableEmptiesTheFifo) {
  chip().reg_write(kDmaCtrl, kDmaRxEn | kDmaTxEn);
  dma_write(1);
  start(0x5005, 0x0905);
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_TRUE(high(Pin::DMAREQR));
  chip().reg_write(kDmaCtrl, 0);
  EXPECT_EQ(chip().reg_read(kDmaCtrl), 0);  // FIFOs and counts at once
  // The requests at the next MCLK edge (datasheet 3.5.1 t_MCLD; dma_port_test.cpp).
  ring.scheduler.run_until(ceil_to(now(), t.mclk()));
  EXPECT_FALSE(high(Pin::DMAREQR));
  EXPECT_FALSE(high(Pin::DMAREQT));
}

TEST_F(Dma, WholeCycleCallsBehaveAsThePins) {
  // DmaPort::acknowledge_read / acknowledge_write: the C++ shortcut for one DMA cycle.
  chip().reg_write(kDmaCtrl, kDmaRxEn | kDmaTxEn);
  DmaPort& port = *chip().unit<DmaPort>();
  port.acknowledge_write(0x1234);
  EXPECT_EQ(port.transmit_count(), 1u);
  start(0x5105, 0x0905);
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_EQ(port.receive_count(), 3u);
  EXPECT_EQ(port.acknowledge_read(), 0x1234);
  EXPECT_EQ(port.acknowledge_read(), 0);
  EXPECT_EQ(port.acknowledge_read(), 0);
  EXPECT_FALSE(high(Pin::DMAREQR));
  EXPECT_EQ(port.acknowledge_read(), 0xFFFF);  // underrun: the floating bus
}

class Dma8Bit : public Dma {
 protected:
  Dma8Bit() : Dma(config()) {}
  static ChipConfig config() {
    ChipConfig c;
    c.buswidth = false;
    return c;
  }
  std::uint8_t byte_read(unsigned a0) {
    chip().drive(Pin::A0, sim::level_of(a0 != 0));
    chip().drive(Pin::DMAACKRN, Level::Low);
    chip().drive(Pin::RDN, Level::Low);
    std::uint8_t b = 0;
    for (unsigned bit = 0; bit < 8; ++bit) {
      if (chip().input_high(data_pin(bit))) b = static_cast<std::uint8_t>(b | 1u << bit);
    }
    ring.run_for(kStrobe);
    chip().drive(Pin::RDN, Level::High);
    chip().drive(Pin::DMAACKRN, Level::High);
    ring.run_for(kStrobe);
    return b;
  }
};

TEST_F(Dma8Bit, AWordIsTwoByteReadsAndDmareqrDropsAtTheFirstOfTheLast) {
  // 8-bit bus (Table 1 BUSWIDTH = 0, BYTEDIR = 0: A0 = 0 is the low byte): the word
  // leaves the FIFO with its A0 = 1 byte; DMAREQR drops when the last word's read begins.
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905);
  ring.scheduler.run_until(detected(kData));
  EXPECT_EQ(byte_read(0), 0x11);
  EXPECT_EQ(byte_read(1), 0x11);
  EXPECT_EQ(byte_read(0), 0x22);
  EXPECT_EQ(byte_read(1), 0x22);
  EXPECT_TRUE(high(Pin::DMAREQR));
  const Time last = now();
  EXPECT_EQ(byte_read(0), 0x33);
  EXPECT_EQ(reqr.back(), std::make_pair(last, Level::Low));
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 1u);
  EXPECT_EQ(byte_read(1), 0x33);
  EXPECT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 0u);
}

// docs/chip.md "Byte lanes" decision: "the even byte (A0 = 0) always travels on D7-0 and
// the odd byte on D15-8; BYTEDIR says which half of the word the even byte is. So a 16-bit
// word access with BYTEDIR = 1 carries the word byte-swapped on D15-0". docs/telegram-
// processing.md "DMA": 8-bit DMA accesses take "bytes by BYTEDIR as for RAM". 16-bit DMA
// accesses do the same: on a BYTEDIR = 1 board a telegram word appears on D15-0 as a RAM
// read of it gives it, and a word the DMA controller writes goes on the line in the byte
// order of the same D15-0 written to a RAM container. (A big-endian host, for which
// BYTEDIR = 1 is meant, would otherwise get every DMA word byte-swapped.)
class DmaByteDir : public Dma {
 protected:
  DmaByteDir() : Dma(config()) {}
  static ChipConfig config() {
    ChipConfig c;
    c.bytedir = true;  // 16-bit bus (BUSWIDTH = 1), high byte first
    return c;
  }
  static constexpr std::array<std::uint16_t, 3> kWords{0x1122, 0x3344, 0x5566};

  // D15-0 of a 16-bit RAM read / write cycle (MCSN0 = MCSN1 = 0, BHEN = 0) of word `at`.
  std::uint16_t ram_cycle_read(std::uint16_t at) {
    BusCycle c;
    c.address = static_cast<std::uint16_t>(2 * at);
    c.bhen = false;
    c.mcsn0 = c.mcsn1 = false;
    return chip().bus(c).data;
  }
  void ram_cycle_write(std::uint16_t at, std::uint16_t data) {
    BusCycle c;
    c.write = true;
    c.address = static_cast<std::uint16_t>(2 * at);
    c.data = data;
    c.bhen = false;
    c.mcsn0 = c.mcsn1 = false;
    chip().bus(c);
  }
};

// Receive: the RAM container's words go out, come back and enter the receive FIFO; each
// must appear on D15-0 of the DMA read as it does on D15-0 of a RAM read of that word.
TEST_F(DmaByteDir, DmaReadPutsAWordOnD15To0AsARamReadDoes) {
  chip().reg_write(kDmaCtrl, kDmaRxEn);
  start(0x5005, 0x0905, kWords);  // transmit from RAM every cycle; receive ACHK + DMA
  ring.run_for(kTscyc * sim::kMicrosecond);
  ASSERT_EQ(rxcnt(chip().reg_read(kDmaCtrl)), 3u);  // the 3 words are in
  for (const std::uint16_t at : std::array<std::uint16_t, 3>{0x045, 0x046, 0x047}) {
    const std::uint16_t ram = ram_cycle_read(at);
    EXPECT_EQ(dma_read(), ram) << "RAM word " << at << " reads 0x" << std::hex << ram
                               << " on D15-0";
  }
  // The word API gives logical values on every board (docs/chip.md "Word API").
  EXPECT_EQ(chip().ram_read(0x045), kWords[0]);
}

// Transmit: D15-0 written by the DMA controller must go on the line as the same D15-0
// written to a RAM container by a RAM write cycle would.
TEST_F(DmaByteDir, DmaWriteTakesD15To0AsARamWriteDoes) {
  chip().reg_write(kDmaCtrl, kDmaTxEn);
  std::vector<std::uint8_t> expected;
  for (const std::uint16_t data : std::array<std::uint16_t, 3>{0xAABB, 0xCCDD, 0xEEFF}) {
    dma_write(data);
    ram_cycle_write(0x100, data);  // a spare word: what a RAM container would hold
    const std::uint16_t word = chip().ram_read(0x100);
    expected.push_back(static_cast<std::uint8_t>(word & 0xFF));  // little-endian (facts §2)
    expected.push_back(static_cast<std::uint8_t>(word >> 8));
  }
  start(0x5105, 0x0805);  // transmit with DMA = 1
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_EQ(list_data(), expected);
}

// The word API's whole DMA cycles move logical words on every board, as ram_read /
// ram_write do (docs/chip.md "Word API"): BYTEDIR changes nothing there.
TEST_F(DmaByteDir, WholeCycleCallsMoveLogicalWords) {
  chip().reg_write(kDmaCtrl, kDmaRxEn | kDmaTxEn);
  DmaPort& port = *chip().unit<DmaPort>();
  port.acknowledge_write(0x1234);
  start(0x5105, 0x0905);  // the FIFO's word goes out and comes back into the receive FIFO
  ring.run_for(kTscyc * sim::kMicrosecond);
  ASSERT_EQ(port.receive_count(), 3u);
  EXPECT_EQ(port.acknowledge_read(), 0x1234);
}

}  // namespace
}  // namespace sercon::chip
