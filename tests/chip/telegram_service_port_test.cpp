// The hand-over of SVFL containers to the service-container engine (datasheet 4.2.2 SVFL,
// NSV, SCMASTER; delta spec 2.10.2 INT_RSCEND; docs/telegram-processing.md, "Service
// channel port"), with a recording port in place of the engine, and the pass-through
// default.
#include <gtest/gtest.h>

#include <vector>

#include "sercon/chip/service_channel_port.hpp"
#include "sercon/chip/telegram_processor.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 100;
constexpr Time kWork = 3 * sim::kMicrosecond;

struct Call {
  ServiceContainerUse use;
  std::vector<std::uint16_t> words;
  bool error_free = false;
};

class RecordingPort final : public ServiceChannelPort {
 public:
  void before_transmit(const ServiceContainerUse& use, std::span<std::uint16_t> words) override {
    transmits.push_back({use, {words.begin(), words.end()}, true});
    words[0] = 0x0F03;  // the engine's MDT control word
  }
  sim::Time after_receive(const ServiceContainerUse& use, std::span<const std::uint16_t> words,
                          bool error_free) override {
    receives.push_back({use, {words.begin(), words.end()}, error_free});
    return kWork;
  }
  std::vector<Call> transmits, receives;
};

class ServicePort : public ::testing::Test {
 protected:
  ServicePort() : ring(1, kFibre) {}

  // Master loop: a telegram to 5 with two containers, the first one SVFL (container 3,
  // master coding); a receive header for it with the same split.
  // double_buffer: the transmit telegram double-buffered with VAL = 1 (buffer 1 goes out;
  // buffer 0 holds other words).
  void start(bool double_buffer = false) {
    t = timing_16mbit();
    Chip& m = ring.chip(0);
    program_master(m, t, kTscyc, 4);
    words(m, 0x000, {0x060, 0x040});
    if (double_buffer) {
      transmit_header(m, 0x040, 0x5005 | telegram::kDbuf | telegram::kVal, 20, 3, 0x050);
      words(m, 0x044,
            {0x4400 | 3 << 11 | 2, 0xAAAA, 0xAAAB, 0x0001, 0x0000, 0x8001, 0xDEAD, 0xCAFE});
    } else {
      transmit_header(m, 0x040, 0x5005, 20, 3, 0x050);
      words(m, 0x044, {0x4400 | 3 << 11 | 2, 0x0001, 0x0000, 0x8001, 0xCAFE});
    }
    receive_header(m, 0x050, 0x0805, 0, 3, 0x060);
    words(m, 0x055, {0x4400 | 3 << 11 | 2, 0, 0, 0, 0x8001, 2, 0});
    end_marker(m, 0x060, 90);
    m.reg_write(kWdCtrl, 0);
    enable_transmission(m);
    ring.run_for(555'555);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    start_master(m);
  }
  Chip& chip() { return ring.chip(0); }
  TelegramProcessor& tp() { return *ring.stations[0].tp; }
  const Seen& list_telegram() const {
    for (const Seen& s : ring.fibres[0]->seen) {
      if (s.data.size() != 1) return s;
    }
    static const Seen none;
    return none;
  }
  // The detection in cycle 0 of the telegram with these data bytes, back at the receiver.
  Time detected(const std::vector<std::uint8_t>& data) const {
    const Time start = on_bit_grid(cycle_time(first, 20, t), t);
    return detection(start + kFibre + static_cast<Time>(line_bits(5, data)) * t.bit, t);
  }

  Ring ring;
  Timing t;
  Time first = 0;
};

TEST_F(ServicePort, SvflContainersPassThroughThePortBothWays) {
  RecordingPort port;
  tp().set_service_channel_port(&port);
  start();
  ring.run_for(kTscyc * sim::kMicrosecond);
  ASSERT_EQ(port.transmits.size(), 1u);
  EXPECT_EQ(port.transmits[0].use.number, 3);
  EXPECT_TRUE(port.transmits[0].use.master);
  EXPECT_EQ(port.transmits[0].use.control_word, 0x044);
  EXPECT_EQ(port.transmits[0].use.data_address, 0x045);
  EXPECT_EQ(port.transmits[0].words, (std::vector<std::uint16_t>{0x0001, 0x0000}));
  // What the engine left in the words is what went out; the second container as it is.
  EXPECT_EQ(list_telegram().data, (std::vector<std::uint8_t>{0x03, 0x0F, 0x00, 0x00, 0xFE, 0xCA}));
  ASSERT_EQ(port.receives.size(), 1u);
  EXPECT_EQ(port.receives[0].use.number, 3);
  EXPECT_EQ(port.receives[0].use.control_word, 0x055);
  EXPECT_EQ(port.receives[0].use.data_address, 0x057);
  EXPECT_EQ(port.receives[0].words, (std::vector<std::uint16_t>{0x0F03, 0x0000}));
  EXPECT_TRUE(port.receives[0].error_free);
  // The words are in the DPRAM containers as well.
  EXPECT_EQ(chip().ram_read(0x057), 0x0F03);
  EXPECT_EQ(chip().ram_read(0x05B), 0xCAFE);
}

// Datasheet 4.2.1 VAL: with double buffering VAL = 1 names buffer 1, which goes out; the
// engine is told that buffer's address (ServiceContainerUse::data_address, "the buffer"),
// as the receive side tells the buffer it wrote.
TEST_F(ServicePort, ADoubleBufferedContainerNamesTheBufferThatGoesOut) {
  RecordingPort port;
  tp().set_service_channel_port(&port);
  start(true);
  ring.run_for(kTscyc * sim::kMicrosecond);
  ASSERT_EQ(port.transmits.size(), 1u);
  EXPECT_EQ(port.transmits[0].use.control_word, 0x044);
  EXPECT_EQ(port.transmits[0].use.data_address, 0x047);  // data 0x045 + LEN 2: buffer 1
  EXPECT_EQ(port.transmits[0].words, (std::vector<std::uint16_t>{0x0001, 0x0000}));
  EXPECT_EQ(list_telegram().data, (std::vector<std::uint8_t>{0x03, 0x0F, 0x00, 0x00, 0xFE, 0xCA}));
}

TEST_F(ServicePort, RscendComesWhenTheEngineIsDone) {
  // Delta spec 2.10.2.2: INT_RSCEND "becomes active, at the end of a receive telegram, if
  // there are no service container that need to be worked on or in case the work is
  // completed".
  RecordingPort port;
  tp().set_service_channel_port(&port);
  start();
  const Time done = detected({0x03, 0x0F, 0x00, 0x00, 0xFE, 0xCA}) + kWork;
  ring.scheduler.run_until(done - 1);
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntRend);
  EXPECT_FALSE(chip().reg_read(kWdCtrl) & kIntRscend);
  ring.scheduler.run_until(done);
  EXPECT_TRUE(chip().reg_read(kWdCtrl) & kIntRscend);
}

TEST_F(ServicePort, WithoutAnEngineRscendComesAtTheEndOfTheTelegram) {
  start();  // pass-through port: words as they are, no work
  const Time end = detected({0x01, 0x00, 0x00, 0x00, 0xFE, 0xCA});
  ring.scheduler.run_until(end - 1);
  EXPECT_FALSE(chip().reg_read(kWdCtrl) & kIntRscend);
  ring.scheduler.run_until(end);
  EXPECT_TRUE(chip().reg_read(kWdCtrl) & kIntRscend);
  EXPECT_EQ(list_telegram().data, (std::vector<std::uint8_t>{0x01, 0x00, 0x00, 0x00, 0xFE, 0xCA}));
}

TEST_F(ServicePort, AnErroredTelegramIsReportedAsSuch) {
  RecordingPort port;
  tp().set_service_channel_port(&port);
  ring.fibres[0]->corrupt(2, 40);
  start();
  ring.run_for(kTscyc * sim::kMicrosecond);
  ASSERT_EQ(port.receives.size(), 1u);
  EXPECT_FALSE(port.receives[0].error_free);
}

}  // namespace
}  // namespace sercon::chip
