// BUSYN: "becomes active if an access to an address of the dual port RAM is performed
// simultaneously to an access to the same memory location by the internal telegram
// processing" (datasheet Table 1); "has to have a maximum length of one cycle of MCLK"
// (delta spec 2.8). Times are exact picoseconds on the MCLK grid from time 0.
#include <gtest/gtest.h>

#include <array>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "chip_fixture.hpp"
#include "sercon/chip/dma_port.hpp"
#include "sercon/chip/service_channel_port.hpp"
#include "sercon/chip/telegram_list.hpp"
#include "sercon/chip/telegram_ram.hpp"
#include "sercon/chip/telegram_receive.hpp"
#include "sercon/chip/telegram_transmit.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::ChipOnBench;

// Records every BUSYN edge with its time.
struct EdgeLog {
  EdgeLog(ChipOnBench& bench, Pin p) {
    bench.chip->pin(p).watch(
        [this, &bench](Level l) { edges.emplace_back(bench.scheduler.now(), l); });
  }
  std::vector<std::pair<Time, Level>> edges;
};

ChipConfig mclk(std::int64_t hz) {
  ChipConfig c;
  c.mclk_hz = hz;
  return c;
}

TEST(Busy, SameWordInTheSameMclkPeriodPullsBusynLowUntilTheNextEdge) {
  ChipOnBench bench(mclk(32'000'000));  // T = 31 250 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(100'000);  // period 3 runs 93 750 .. 125 000
  bench.chip->tp_ram_write(0x0123, 0x4444);
  bench.scheduler.run_until(110'000);
  EXPECT_EQ(bench.chip->ram_read(0x0123), 0x4444);  // the µP sees the new value
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::Low);
  bench.scheduler.run_until(200'000);
  ASSERT_EQ(log.edges.size(), 2u);
  EXPECT_EQ(log.edges[0], std::make_pair(Time{110'000}, Level::Low));
  EXPECT_EQ(log.edges[1], std::make_pair(Time{125'000}, Level::High));
  EXPECT_LE(log.edges[1].first - log.edges[0].first, bench.chip->mclk_period());
}

TEST(Busy, AnAccessAtThePeriodStartLastsExactlyOneMclk) {
  ChipOnBench bench(mclk(64'000'000));  // T = 15 625 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(15'625 * 4);
  bench.chip->tp_ram_read(7);
  bench.chip->ram_write(7, 1);
  bench.scheduler.run_until(15'625 * 10);
  ASSERT_EQ(log.edges.size(), 2u);
  EXPECT_EQ(log.edges[0].first, 15'625 * 4);
  EXPECT_EQ(log.edges[1].first, 15'625 * 5);
}

TEST(Busy, OtherWordOrOtherPeriodDoesNotCollide) {
  ChipOnBench bench(mclk(32'000'000));
  EdgeLog log(bench, Pin::BUSYN);
  bench.chip->tp_ram_read(10);
  bench.chip->ram_read(11);           // another word
  bench.scheduler.run_until(31'250);  // next period
  bench.chip->ram_read(10);
  bench.scheduler.run_until(1'000'000);
  EXPECT_TRUE(log.edges.empty());
}

// The bus cycle reports the collision; a µP that touches the word first is not delayed.
TEST(Busy, BusResultReportsTheCollision) {
  ChipOnBench bench;
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  c.address = 0x0040;
  EXPECT_FALSE(bench.chip->bus(c).busy);
  bench.chip->tp_ram_write(0x0020, 0xFFFF);
  EXPECT_TRUE(bench.chip->bus(c).busy);
  EXPECT_TRUE(bench.chip->bus(c).busy);  // again in the same period: still busy
  c.address = 0x0042;
  EXPECT_FALSE(bench.chip->bus(c).busy);
}

// Several collisions in one period give one low pulse; a collision in the next period
// (after the rise) gives a second one.
TEST(Busy, RepeatedCollisionsStayWithinOnePeriodEach) {
  ChipOnBench bench(mclk(50'000'000));  // T = 20 000 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(5'000);
  bench.chip->tp_ram_write(1, 1);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(9'000);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(20'000);
  bench.chip->tp_ram_write(1, 2);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(100'000);
  const std::vector<std::pair<Time, Level>> expected = {
      {5'000, Level::Low}, {20'000, Level::High}, {20'000, Level::Low}, {40'000, Level::High}};
  EXPECT_EQ(log.edges, expected);
}

// A reset ends a busy pulse at once (BUSYN inactive after reset).
TEST(Busy, ResetReleasesBusyn) {
  ChipOnBench bench;
  bench.chip->tp_ram_read(3);
  bench.chip->ram_read(3);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::Low);
  bench.chip->reg_write(0x01, 0x0002);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::High);
  bench.scheduler.run_until(1'000'000);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::High);
}

// Table 1 BUSYN: an access "performed simultaneously to an access to the same memory
// location by the internal telegram processing". Two events at the same picosecond run in
// the order they were scheduled, which the chip cannot know: a µP access whose event runs
// just before the telegram processor's at the same instant collides as the reverse order
// does (BusResultReportsTheCollision: the µP's access itself is not delayed). A telegram
// processor access later in the period does not pull BUSYN for an access already made
// (datasheet 3.5.5 / 3.5.7 t_MBSY: BUSYN falls within 15 ns of the strobe's start).
TEST(Busy, InternalAccessAtTheInstantOfAHostAccessCollidesWhicheverRunsFirst) {
  for (const int kind : {0, 1, 2}) {      // one word, a run over it, a word beside it
    ChipOnBench bench(mclk(32'000'000));  // period 3 runs 93 750 .. 125 000
    EdgeLog log(bench, Pin::BUSYN);
    Chip& chip = *bench.chip;
    bench.scheduler.at(100'000, [&chip] { chip.ram_read(0x0123); });
    bench.scheduler.at(100'000, [&chip, kind] {
      const std::array<std::uint16_t, 3> words{1, 2, 3};
      if (kind == 0) chip.tp_ram_write(0x0123, 0x4444);
      if (kind == 1) chip.tp_ram_write_run(0x0122, words);
      if (kind == 2) chip.tp_ram_write(0x0124, 0x4444);
    });
    bench.scheduler.at(110'000, [&chip] { chip.tp_ram_read(0x0123); });  // later: no effect
    bench.scheduler.run_until(200'000);
    using E = std::pair<Time, Level>;
    const std::vector<E> expected =
        kind == 2 ? std::vector<E>{}
                  : std::vector<E>{{100'000, Level::Low}, {125'000, Level::High}};
    EXPECT_EQ(log.edges, expected) << kind;
  }
}

TEST(Busy, InternalPortCountsItsAccessesNotTheHosts) {
  ChipOnBench bench;
  bench.chip->tp_ram_read(1);
  bench.chip->tp_ram_write(2, 2);
  bench.chip->ram_read(1);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 2u);
}

TEST(Busy, InternalPortChecksTheAddress) {
  ChipOnBench bench;
  EXPECT_THROW(bench.chip->tp_ram_read(2048), std::out_of_range);
  EXPECT_THROW(bench.chip->tp_ram_write(2048, 0), std::out_of_range);
}

// A run through the internal port is the same as one access per word: every word of it
// collides in the period, the words beside it do not, and each counts as an access.
TEST(Busy, RunOfWordsMarksEachWordLikeSingleAccesses) {
  ChipOnBench bench(mclk(32'000'000));
  bench.scheduler.run_until(100'000);
  const std::array<std::uint16_t, 3> words{0x1111, 0x2222, 0x3333};
  bench.chip->tp_ram_write_run(0x0100, words);
  std::array<std::uint16_t, 3> back{};
  bench.chip->tp_ram_read_run(0x0100, back);
  EXPECT_EQ(back, words);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 6u);
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  for (std::uint16_t w = 0x00FF; w <= 0x0103; ++w) {
    c.address = static_cast<std::uint16_t>(2 * w);  // byte address of the word
    EXPECT_EQ(bench.chip->bus(c).busy, w >= 0x0100 && w <= 0x0102) << w;
  }
}

// What one gather left behind: the bytes (none after a fault), the accesses it made, the
// words it used in the period (BUSYN against a µP access), and any list fault's message.
struct Gathered {
  std::vector<std::uint8_t> data;
  std::uint64_t accesses = 0;
  std::vector<std::uint16_t> busy_words;
  std::string fault;
  std::vector<std::pair<ServiceContainerUse, std::vector<std::uint16_t>>> service;
};

// A service-container engine that sees the words as read and replaces them (service
// channel port: "the engine may replace them ... What it leaves there goes on the line").
struct ReplacingPort final : ServiceChannelPort {
  void before_transmit(const ServiceContainerUse& use, std::span<std::uint16_t> words) override {
    seen.emplace_back(use, std::vector<std::uint16_t>(words.begin(), words.end()));
    for (std::uint16_t& w : words) w = static_cast<std::uint16_t>(0xA000 | (w & 0x0FFF));
  }
  sim::Time after_receive(const ServiceContainerUse&, std::span<const std::uint16_t>,
                          bool) override {
    return 0;
  }
  std::vector<std::pair<ServiceContainerUse, std::vector<std::uint16_t>>> seen;
};

// A single-buffer transmit header (CYCL, address 1, TRT 20, TLEN `tlen`) at `header` with
// the words after it, gathered at 100 ns (TransmitPath, docs/telegram-processing.md,
// "Transmit" step 8).
Gathered gather_at(std::uint16_t header, std::uint16_t tlen,
                   const std::vector<std::uint16_t>& after) {
  ChipOnBench bench(mclk(32'000'000));
  Chip& chip = *bench.chip;
  const std::vector<std::uint16_t> head{0x5001, 20, tlen, 0x0200};
  for (std::size_t i = 0; i < head.size(); ++i)
    chip.ram_write(static_cast<std::uint16_t>(header + i), head[i]);
  for (std::size_t i = 0; i < after.size() && header + 4 + i < 2048; ++i)
    chip.ram_write(static_cast<std::uint16_t>(header + 4 + i), after[i]);
  bench.scheduler.run_until(100'000);
  TelegramRam ram(chip);
  DmaPort dma(chip);
  TransmitPath path(ram, dma);
  ReplacingPort port;
  ListItem item;
  item.kind = telegram::Kind::Transmit;
  item.address = header;
  item.word0 = head[0];
  item.time = 20;
  item.length = tlen;
  item.next = 0x0200;
  Gathered g;
  const std::uint64_t before = chip.tp_ram_accesses();
  try {
    const std::span<const std::uint8_t> data = path.gather(item, false, port);
    g.data.assign(data.begin(), data.end());
  } catch (const ListFault& f) {
    g.fault = f.what();
  }
  g.accesses = chip.tp_ram_accesses() - before;
  g.service = port.seen;
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  for (std::uint32_t w = header; w < 2048 && w < header + 4u + after.size(); ++w) {
    c.address = static_cast<std::uint16_t>(2 * w);  // byte address of the word
    if (chip.bus(c).busy) g.busy_words.push_back(static_cast<std::uint16_t>(w));
  }
  return g;
}

std::vector<std::uint16_t> word_range(std::uint16_t first, std::uint16_t last) {
  std::vector<std::uint16_t> out;
  for (std::uint32_t w = first; w <= last; ++w) out.push_back(static_cast<std::uint16_t>(w));
  return out;
}

// A telegram whose containers are all plain is gathered as one run of words (TransmitPath):
// it uses exactly the words one read per container would, its control words and data, at
// that instant: each collides with a µP access in the period and counts as an access, the
// header and the words after the last container do not.
TEST(Busy, PlainTransmitContainersAreUsedWordByWord) {
  // Containers of 3 and 2 words after the header (TLEN 5), then a word not used.
  const Gathered g =
      gather_at(0x0100, 5, {0x0003, 0x1111, 0x2222, 0x3333, 0x8002, 0x4444, 0x5555, 0x7777});
  const std::vector<std::uint8_t> expected{0x11, 0x11, 0x22, 0x22, 0x33,
                                           0x33, 0x44, 0x44, 0x55, 0x55};
  EXPECT_EQ(g.data, expected);
  EXPECT_EQ(g.fault, "");
  EXPECT_EQ(g.accesses, 7u);  // 2 control words, 5 data words
  EXPECT_EQ(g.busy_words, word_range(0x0104, 0x010A));
}

// A chip whose RAM holds `words` from `header` on, at 100 ns, after a µP access to
// `host_word` at that instant (none for 2048 and above): the bench of the twin tests below,
// which run a direct and a general path on two such chips and compare what each left.
struct TwinBench {
  TwinBench(std::uint16_t at, const std::vector<std::uint16_t>& words, std::uint32_t host)
      : header(at), host_word(host) {
    for (std::size_t i = 0; i < words.size(); ++i)
      chip.ram_write(static_cast<std::uint16_t>(header + i), words[i]);
    bench.scheduler.run_until(100'000);
    if (host_word < 2048) access(host_word);
  }
  bool access(std::uint32_t word) {
    BusCycle c;
    c.mcsn0 = false;
    c.mcsn1 = false;
    c.bhen = false;
    c.address = static_cast<std::uint16_t>(2 * word);  // byte address of the word
    return chip.bus(c).busy;
  }
  // After the path ran: without a µP access of its own, the words of `span` from the header
  // a µP access collides with now (each pulls BUSYN low, so not along with the edges of a µP
  // access before the path); then, once BUSYN is high again (a µP read collides with none),
  // the BUSYN edges and the RAM.
  void look(std::uint16_t span, std::vector<std::uint16_t>& busy_words,
            std::vector<std::pair<Time, Level>>& edges, std::vector<std::uint16_t>& ram) {
    if (host_word >= 2048) {
      for (std::uint16_t w = header; w < header + span; ++w)
        if (access(w)) busy_words.push_back(w);
    }
    bench.scheduler.run_until(300'000);
    edges = log.edges;
    for (std::uint16_t w = header; w < header + span; ++w) ram.push_back(chip.ram_read(w));
  }
  // The list item the walk makes of the header (time 20, next 0x0200, as in its words).
  ListItem item(telegram::Kind kind, std::uint16_t word0, std::uint16_t tlen) const {
    ListItem i;
    i.kind = kind;
    i.address = header;
    i.word0 = word0;
    i.time = 20;
    i.length = tlen;
    i.next = 0x0200;
    return i;
  }
  ChipOnBench bench{mclk(32'000'000)};
  Chip& chip = *bench.chip;
  EdgeLog log{bench, Pin::BUSYN};
  std::uint16_t header;
  std::uint32_t host_word;
};

// What one receive finish left behind: the RAM around the header, the accesses it made,
// the BUSYN edges after a µP access to `host_word` at the same instant, or without one the
// words a µP access at that instant collides with, and whether the direct path
// (finish_plain) took the telegram.
struct Received {
  std::vector<std::uint16_t> ram;
  std::uint64_t accesses = 0;
  std::vector<std::uint16_t> busy_words;
  std::vector<std::pair<Time, Level>> edges;
  bool direct = false;
  bool operator==(const Received&) const = default;
};

// A receive header at 0x0100 (word 0 `word0`, TLEN `tlen`) with one container (control word
// `control`, POS `pos`, 4 buffer words) finished at 100 ns with `frame`: by finish_plain
// first (`direct`) or by the general finish() only.
Received receive_at(bool direct, std::uint16_t word0, std::uint16_t tlen, std::uint16_t control,
                    std::uint16_t pos, const wire::DecodedFrame& frame, std::uint32_t host_word) {
  constexpr std::uint16_t kHeader = 0x0100;
  TwinBench twin(kHeader,
                 {word0, 20, tlen, 0x0200, 7, control, pos, 0xAAAA, 0xBBBB, 0xCCCC, 0xDDDD, 0xEEEE},
                 host_word);
  TelegramRam ram(twin.chip);
  DmaPort dma(twin.chip);
  ReceivePath path(ram, dma);
  PassThroughServiceChannel port;
  const ListItem item = twin.item(telegram::Kind::Receive, word0, tlen);
  Received r;
  const std::uint64_t before = twin.chip.tp_ram_accesses();
  r.direct = direct && path.finish_plain(item, frame);
  if (!r.direct) path.finish(item, frame, port);
  r.accesses = twin.chip.tp_ram_accesses() - before;
  twin.look(16, r.busy_words, r.edges, r.ram);
  return r;
}

// The direct path of the usual receive telegram (ReceivePath::finish_plain) leaves exactly what
// the general one does: RAM, accesses, the words used and BUSYN against a µP access at that
// instant; any other telegram it leaves alone (nothing read, written or marked).
TEST(Busy, PlainReceiveFinishesAsTheGeneralPath) {
  wire::DecodedFrame frame;
  frame.address = 9;
  frame.data = {0x11, 0x12, 0x21, 0x22, 0x31, 0x32};
  for (const std::uint16_t word0 : {std::uint16_t{0x0009}, std::uint16_t{0x0C09}}) {  // ACHK
    for (const int p : {0, 1, 2, 3, 5}) {
      const auto pos = static_cast<std::uint16_t>(p);
      for (const std::uint32_t host : {0x0100u, 0x0105u, 0x0107u, 0x0108u, 0x0109u, 0xFFFFu}) {
        const Received general = receive_at(false, word0, 3, 0x8003, pos, frame, host);
        const Received direct = receive_at(true, word0, 3, 0x8003, pos, frame, host);
        EXPECT_TRUE(direct.direct);
        EXPECT_EQ(direct.ram, general.ram) << word0 << " " << pos << " " << host;
        EXPECT_EQ(direct.accesses, general.accesses);
        EXPECT_EQ(direct.busy_words, general.busy_words);
        EXPECT_EQ(direct.edges, general.edges);
        if (host == 0x0100) {
          EXPECT_EQ(direct.edges.size(), 2u);  // word 0 always collides
        }
        if (host >= 2048) {  // word 0 and the control word are always used
          ASSERT_GE(general.busy_words.size(), 2u);
          EXPECT_EQ(general.busy_words[0], 0x0100);
          EXPECT_EQ(general.busy_words[1], 0x0105);
        }
      }
    }
  }
  // DMA, double buffer, a service container, no LASTDC, a frame error, a length other than
  // TLEN: finish_plain declines and leaves nothing behind (the same as the general path alone).
  wire::DecodedFrame bad = frame;
  bad.error = wire::FrameError::BadFcs;
  wire::DecodedFrame longer = frame;
  longer.data.push_back(0x41);
  longer.data.push_back(0x42);
  const std::vector<std::tuple<std::uint16_t, std::uint16_t, wire::DecodedFrame>> others{
      {0x0109, 0x8003, frame}, {0x0209, 0x8003, frame}, {0x0009, 0x8403, frame},
      {0x0009, 0x0003, frame}, {0x0009, 0x8003, bad},   {0x0009, 0x8003, longer}};
  for (const auto& [word0, control, f] : others) {
    const Received general = receive_at(false, word0, 3, control, 0, f, 0x0100);
    const Received direct = receive_at(true, word0, 3, control, 0, f, 0x0100);
    EXPECT_FALSE(direct.direct) << word0 << " " << control;
    EXPECT_EQ(direct, general) << word0 << " " << control;
  }
}

// What one transmit start left behind (TransmitPath): the bytes gathered, the RAM around
// the header, the accesses, the BUSYN edges after a µP access to `host_word` at the same
// instant, or without one the words a µP access at that instant collides with, and whether
// the direct path (gather_plain) took the telegram.
struct Transmitted {
  std::vector<std::uint8_t> data;
  std::vector<std::uint16_t> ram;
  std::uint64_t accesses = 0;
  std::vector<std::uint16_t> busy_words;
  std::vector<std::pair<Time, Level>> edges;
  bool direct = false;
  bool operator==(const Transmitted&) const = default;
};

// A transmit header at 0x0100 (word 0 `word0`, TLEN `tlen`) with the words `after` it,
// started at 100 ns: by gather_plain first (`direct`) or by the general reread_val, EN
// written back and gather() only, as TelegramProcessor::transmit_due does.
Transmitted transmit_at(bool direct, std::uint16_t word0, std::uint16_t tlen,
                        const std::vector<std::uint16_t>& after, std::uint32_t host_word) {
  constexpr std::uint16_t kHeader = 0x0100;
  std::vector<std::uint16_t> words{word0, 20, tlen, 0x0200};
  words.insert(words.end(), after.begin(), after.end());
  TwinBench twin(kHeader, words, host_word);
  TelegramRam ram(twin.chip);
  DmaPort dma(twin.chip);
  TransmitPath path(ram, dma);
  ReplacingPort port;
  const ListItem item = twin.item(telegram::Kind::Transmit, word0, tlen);
  Transmitted t;
  const std::uint64_t before = twin.chip.tp_ram_accesses();
  std::span<const std::uint8_t> data;
  t.direct = direct && path.gather_plain(item, data);
  if (!t.direct) {
    const bool val = path.reread_val(item);
    if (item.has(telegram::kEn)) path.clear_send_once(item, val);
    data = path.gather(item, val, port);
  }
  t.data.assign(data.begin(), data.end());
  t.accesses = twin.chip.tp_ram_accesses() - before;
  twin.look(20, t.busy_words, t.edges, t.ram);
  return t;
}

// The direct path of the usual transmit telegram (TransmitPath::gather_plain) leaves exactly
// what the general one does: the bytes, RAM, accesses, the words used and BUSYN against a µP
// access at that instant; any other telegram it leaves alone (nothing read, written or
// marked).
TEST(Busy, PlainTransmitStartsAsTheGeneralPath) {
  // One container of 3 words (sent from the RAM as it is); containers of 1 and 2 words; TLEN
  // beyond the containers' words (the rest goes out as 0), also beyond one container's; a
  // container of 7 words (a run past straight-line marks).
  const std::vector<std::tuple<std::uint16_t, std::vector<std::uint16_t>>> plain{
      {3, {0x8003, 0x1111, 0x2222, 0x3333, 0x7777}},
      {3, {0x0001, 0x1111, 0x8002, 0x2222, 0x3333, 0x7777}},
      {5, {0x0001, 0x1111, 0x8002, 0x2222, 0x3333, 0x7777}},
      {5, {0x8003, 0x1111, 0x2222, 0x3333, 0x7777}},
      {7, {0x8007, 1, 2, 3, 4, 5, 6, 7, 0x7777}}};
  for (const std::uint16_t word0 : {std::uint16_t{0x1001}, std::uint16_t{0x1401}}) {  // VAL
    for (const auto& [tlen, after] : plain) {
      for (const std::uint32_t host : {0x0100u, 0x0101u, 0x0103u, 0x0104u, 0x0105u, 0x0106u,
                                       0x0107u, 0x010Bu, 0x010Cu, 0x010Du, 0xFFFFu}) {
        const Transmitted general = transmit_at(false, word0, tlen, after, host);
        const Transmitted direct = transmit_at(true, word0, tlen, after, host);
        EXPECT_TRUE(direct.direct);
        EXPECT_EQ(direct.data, general.data) << word0 << " " << tlen << " " << host;
        EXPECT_EQ(direct.ram, general.ram);
        EXPECT_EQ(direct.accesses, general.accesses) << word0 << " " << tlen << " " << host;
        EXPECT_EQ(direct.busy_words, general.busy_words) << word0 << " " << tlen << " " << host;
        EXPECT_EQ(direct.edges, general.edges) << word0 << " " << tlen << " " << host;
        if (host == 0x0100) {
          EXPECT_EQ(direct.edges.size(), 2u);  // word 0 always collides
        }
        if (host == 0x0101 || host == 0x0103) {
          EXPECT_TRUE(direct.edges.empty());  // the rest of the header does not
        }
        if (host == 0xFFFF) {
          EXPECT_EQ(direct.busy_words.front(), 0x0100);       // word 0 and the containers' words
          EXPECT_EQ(direct.busy_words.size(), after.size());  // not the word after them
        }
      }
    }
  }
  // EN (send once), DMA, double buffer, a service container, a container beyond TLEN:
  // gather_plain declines and leaves nothing behind (the same as the general path alone).
  const std::vector<std::uint16_t> one{0x8003, 0x1111, 0x2222, 0x3333, 0x7777};
  const std::vector<std::tuple<std::uint16_t, std::uint16_t, std::vector<std::uint16_t>>> others{
      {0x1801, 3, one},
      {0x1101, 3, one},
      {0x1201, 3, {0x8002, 0x1111, 0x2222, 0x3333, 0x4444, 0x7777}},
      {0x1001, 3, {0x8403, 0x1111, 0x2222, 0x3333, 0x7777}},
      {0x1001, 2, one}};
  for (const auto& [word0, tlen, after] : others) {
    const Transmitted general = transmit_at(false, word0, tlen, after, 0x0100);
    const Transmitted direct = transmit_at(true, word0, tlen, after, 0x0100);
    EXPECT_FALSE(direct.direct) << word0 << " " << tlen;
    EXPECT_EQ(direct, general) << word0 << " " << tlen;
  }
}

// The list walk reads a header or end marker as one run of words (TelegramList): exactly
// its words, word 0 and TRT, TLEN, PT or TEND, collide in the period and count as accesses.
TEST(Busy, ListItemsAreUsedWordByWord) {
  struct Client final : ListClient {
    void transmit_due(const ListItem&) override {}
    void receive_missed(const ListItem&) override {}
    void end_reached(const ListItem&) override {}
    void list_fault(const ListFault&) override {}
    sim::Time start_report_delay() const override { return 0; }
    void list_moved() override {}
  };
  for (const bool end_marker : {false, true}) {
    ChipOnBench bench(mclk(32'000'000));
    Chip& chip = *bench.chip;
    const std::uint16_t item = 0x0100;
    chip.ram_write(1, item);  // COMPT1
    // A transmit header due at 20 µs (armed: the walk waits there), or an end marker.
    const std::vector<std::uint16_t> words =
        end_marker ? std::vector<std::uint16_t>{0xC000, 30, 0x7777, 0x7777, 0x7777}
                   : std::vector<std::uint16_t>{0x5001, 20, 3, 0x0200, 0x7777};
    for (std::size_t i = 0; i < words.size(); ++i)
      chip.ram_write(static_cast<std::uint16_t>(item + i), words[i]);
    bench.scheduler.run_until(100'000);
    TelegramRam ram(chip);
    Client client;
    TelegramList list(*chip.unit<TimeBase>(), ram, client);
    const std::uint64_t before = chip.tp_ram_accesses();
    list.start(telegram::kCompt1);
    const std::size_t used = end_marker ? 2 : 4;
    EXPECT_EQ(chip.tp_ram_accesses() - before, 1 + used) << end_marker;  // COMPT1 and the item
    BusCycle c;
    c.mcsn0 = false;
    c.mcsn1 = false;
    c.bhen = false;
    for (std::uint16_t w = item - 1; w < item + words.size(); ++w) {
      c.address = static_cast<std::uint16_t>(2 * w);  // byte address of the word
      EXPECT_EQ(chip.bus(c).busy, w >= item && w < item + used) << w << " " << end_marker;
    }
    list.stop();
  }
}

// The one-run gather takes only telegrams whose containers are all plain; one that starts
// plain and then is not goes the per-container way from its first container, and must use
// what that way uses: each control word and each container's data read once (no word of
// the plain first container counted twice, none left out), at the same instant.
//
// Second container SVFL (datasheet 4.2.2; "through the service channel port where SVFL =
// 1", docs/telegram-processing.md, "Transmit" step 8): the port sees its words as read, with
// NSV, SCMASTER and the addresses of its control word and buffer, and what it leaves goes
// out.
TEST(Busy, APlainContainerThenAServiceContainerIsGatheredContainerByContainer) {
  const std::uint16_t h = 0x0100;
  // 3 plain words, then SVFL | NSV 2 | SCMASTER | LASTDC with 2 words, then a word after.
  const Gathered g =
      gather_at(h, 5, {0x0003, 0x1111, 0x2222, 0x3333, 0xD402, 0x4444, 0x5555, 0x7777});
  EXPECT_EQ(g.fault, "");
  const std::vector<std::uint8_t> expected{0x11, 0x11, 0x22, 0x22, 0x33,
                                           0x33, 0x44, 0xA4, 0x55, 0xA5};
  EXPECT_EQ(g.data, expected);
  EXPECT_EQ(g.accesses, 7u);  // 2 control words, 3 + 2 data words
  EXPECT_EQ(g.busy_words, word_range(h + 4, h + 10));
  ASSERT_EQ(g.service.size(), 1u);
  EXPECT_EQ(g.service[0].first.number, 2);
  EXPECT_TRUE(g.service[0].first.master);
  EXPECT_EQ(g.service[0].first.control_word, h + 8);
  EXPECT_EQ(g.service[0].first.data_address, h + 9);
  EXPECT_EQ(g.service[0].second, (std::vector<std::uint16_t>{0x4444, 0x5555}));
}

// Second container longer than TLEN allows: "the telegram carries exactly TLEN words
// (container words beyond TLEN are dropped)" (docs/telegram-processing.md, "Transmit" step
// 8); the container is read whole, as the per-container way reads it, and cut.
TEST(Busy, APlainContainerThenOneBeyondTlenIsGatheredContainerByContainer) {
  const std::uint16_t h = 0x0100;
  const Gathered g =
      gather_at(h, 4, {0x0003, 0x1111, 0x2222, 0x3333, 0x8002, 0x4444, 0x5555, 0x7777});
  EXPECT_EQ(g.fault, "");
  const std::vector<std::uint8_t> expected{0x11, 0x11, 0x22, 0x22, 0x33, 0x33, 0x44, 0x44};
  EXPECT_EQ(g.data, expected);
  EXPECT_EQ(g.accesses, 7u);
  EXPECT_EQ(g.busy_words, word_range(h + 4, h + 10));
  EXPECT_TRUE(g.service.empty());
}

// TLEN = 0 with two containers: "the telegram carries exactly TLEN words (container words
// beyond TLEN are dropped)" (docs/telegram-processing.md, "Transmit" step 8): no data goes
// out, though both containers are read as the per-container way reads them. The second
// one starts past an empty telegram (under UBSan: no offset applied to its null buffer).
TEST(Busy, ContainersOfATelegramWithTlenZeroAreReadAndDropped) {
  const std::uint16_t h = 0x0100;
  const Gathered g = gather_at(h, 0, {0x0001, 0x1111, 0x8001, 0x2222});
  EXPECT_EQ(g.fault, "");
  EXPECT_TRUE(g.data.empty());
  EXPECT_EQ(g.accesses, 4u);  // 2 control words, 2 data words
  EXPECT_EQ(g.busy_words, word_range(h + 4, h + 7));
  EXPECT_TRUE(g.service.empty());
}

// Second container's data past the RAM's end: a list fault ("a ... container or buffer
// beyond the RAM", docs/telegram-processing.md, "Bad lists"), after the words inside the
// RAM were read as the per-container way reads them (TelegramRam: a run is done word by
// word up to the RAM's end).
TEST(Busy, APlainContainerThenOneBeyondTheRamFaultsAfterTheWordsInside) {
  const std::uint16_t h = 0x07F8;  // containers at 0x7FC (1 word) and 0x7FE (3 words)
  const Gathered g = gather_at(h, 4, {0x0001, 0x1111, 0x8003, 0x2222});
  EXPECT_EQ(g.fault, "list structure beyond the RAM");
  EXPECT_TRUE(g.data.empty());
  EXPECT_EQ(g.accesses, 4u);  // 0x7FC..0x7FF
  EXPECT_EQ(g.busy_words, word_range(0x7FC, 0x7FF));
}

// A list walk that records what the list tells its client.
struct RecordingClient final : ListClient {
  void transmit_due(const ListItem&) override {}
  void receive_missed(const ListItem&) override {}
  void end_reached(const ListItem& item) override { ends.push_back(item); }
  void list_fault(const ListFault& f) override { faults.emplace_back(f.what()); }
  sim::Time start_report_delay() const override { return 0; }
  void list_moved() override {}
  std::vector<ListItem> ends;
  std::vector<std::string> faults;
};

// COMPT1 names `item`, whose words are `words`; the walk starts at 100 ns. Returns the
// accesses the walk made and the words it used in the period (from item - 1 on).
struct Walked {
  std::uint64_t accesses = 0;
  std::vector<std::uint16_t> busy_words;
};
Walked walk_at(ChipOnBench& bench, RecordingClient& client, std::uint16_t item,
               const std::vector<std::uint16_t>& words) {
  Chip& chip = *bench.chip;
  chip.ram_write(1, item);  // COMPT1
  for (std::size_t i = 0; i < words.size(); ++i)
    chip.ram_write(static_cast<std::uint16_t>(item + i), words[i]);
  bench.scheduler.run_until(100'000);
  TelegramRam ram(chip);
  TelegramList list(*chip.unit<TimeBase>(), ram, client);
  Walked w;
  const std::uint64_t before = chip.tp_ram_accesses();
  list.start(telegram::kCompt1);
  w.accesses = chip.tp_ram_accesses() - before;
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  for (std::uint32_t a = item - 1u; a < 2048 && a < item + words.size(); ++a) {
    c.address = static_cast<std::uint16_t>(2 * a);  // byte address of the word
    if (chip.bus(c).busy) w.busy_words.push_back(static_cast<std::uint16_t>(a));
  }
  list.stop();
  return w;
}

// Kind 10 inside the RAM ("kind 10" is a list fault, docs/telegram-processing.md, "Bad
// lists"): the one-run read of headers and end markers leaves it to the word-by-word read,
// which reads word 0 only (its kind says nothing about the words after it): one access and
// one word used besides COMPT1, and the fault's message names kind 10.
TEST(Busy, AKindTenItemUsesOnlyItsWordZero) {
  ChipOnBench bench(mclk(32'000'000));
  RecordingClient client;
  const std::uint16_t item = 0x0100;
  const Walked w = walk_at(bench, client, item, {0x8000, 20, 3, 0x0200, 0x7777});
  EXPECT_EQ(w.accesses, 2u);  // COMPT1 and word 0
  EXPECT_EQ(w.busy_words, std::vector<std::uint16_t>{item});
  ASSERT_EQ(client.faults.size(), 1u);
  EXPECT_EQ(client.faults[0], "list item of kind 10 (neither header nor end marker)");
  EXPECT_TRUE(client.ends.empty());
}

// An end marker (2 words, word 0 and TEND: datasheet 4.2.3) in the RAM's last two words is a
// legal item: too close to the end for the one-run read of 4 words, it is read word by word,
// both words used and counted, and no fault.
TEST(Busy, AnEndMarkerInTheLastTwoWordsIsReadWithoutAFault) {
  ChipOnBench bench(mclk(32'000'000));
  RecordingClient client;
  const std::uint16_t item = 0x07FE;
  const Walked w = walk_at(bench, client, item, {0xC000, 30});
  EXPECT_EQ(w.accesses, 3u);  // COMPT1, word 0, TEND
  EXPECT_EQ(w.busy_words, (std::vector<std::uint16_t>{0x07FE, 0x07FF}));
  EXPECT_TRUE(client.faults.empty());
}

TEST(Busy, RunBeyondTheRamDoesNothing) {
  ChipOnBench bench;
  std::array<std::uint16_t, 2> out{};
  EXPECT_THROW(bench.chip->tp_ram_read_run(2047, out), std::out_of_range);
  EXPECT_THROW(bench.chip->tp_ram_write_run(2047, out), std::out_of_range);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 0u);
}

}  // namespace
}  // namespace sercon::chip
