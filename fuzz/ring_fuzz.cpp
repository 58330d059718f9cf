// libFuzzer target: chips talking to each other. Each input builds a small ring::Ring
// (master + 1..3 slaves, SERCON816 or 410B per node, MCLK, bit rate, fibre lengths) or an
// RS-485 bus of 2..4 chips, optionally brought up as a driver does (lines on, timing
// registers, a CP4 list in every DPRAM), then runs up to 64 operations chosen by the input:
// register writes to any chip (biased towards values that act), DPRAM writes (random words
// and list items from a small grammar), register read-backs, fibre break / restore /
// break_at / restore_at, bit-error rates, a TxD taken off the bus and put back, lazy hops
// switched per chip, and time steps. docs/fuzzing.md, "Chips talking to each other".
//
// Every input runs three times on fresh simulations:
//   A. lazy hops as the input switches them (on by default);
//   B. lazy hops off in every chip all the time;
//   C. A again.
// Invariants (each a statement of the specification or of the project's documented
// contract):
//  1. Nothing the host does through registers and DPRAM, nor the ring's public operations,
//     makes Scheduler::run_until / step throw or crash. The one documented exception is
//     allowed: std::runtime_error "... circle a ring where every node repeats ..." from a
//     receiver holding 1024 changes announced ahead (docs/serial-and-ring.md, "Per telegram,
//     not per bit", depth guard), only in a ring where every node has had REPON = 1.
//  2. Unused register bits read 0 (datasheet 4.1); VERSION per variant (delta spec
//     2.11.1.1); 0x2B..0x3F read 0 (docs/registers.md).
//  3. The telegram processor writes only the DPRAM words it is documented to write
//     (docs/telegram-processing.md §1-§5): word 0 and NERR of receive headers on the walk,
//     word 0 of transmit headers on the walk, receive container buffers, NMSTERR (word 10).
//     Every other word keeps its value through a time step. The walk keeps what it read, so
//     every header reachable so far counts, and the walks go on from the pointer each of
//     them had (writable_words). Checked when those structures do not overlap (a written
//     word that is also a structure word could change the walk mid-step).
//  4. Determinism: A and C give identical observations (docs/telegram-processing.md, "Events
//     at the same picosecond": every tie is deterministic; docs/serial-and-ring.md: a bits
//     object belongs to one simulation, recycled ones carry nothing of their past).
//  5. Lazy hops change nothing anyone can see (docs/serial-and-ring.md, "Lazy hops", "Same
//     results"): A and B give identical observations.
// Observations, each kept as its own stream (the order of events of the same picosecond
// across streams is not observable): every change on every fibre's input (each node's TxD1
// line) and output (each RxD) or on the bus, settled (a SettledLine: what really happens,
// when); levels of INT0, INT1, BUSYN, L_ERRN, IDLE, WDOGN, CYC_CLK, CON_CLK, DIV_CLK,
// DMAREQR/T, TxD1, TxD2 of every chip at every change; each chip's DPRAM after every time
// step; every register of every chip when the input reads them and at the end; fibre
// bit-error counts and bus collisions at the end.
//
// Work per input is bounded as chip_bus_fuzz bounds it: run A stops after 60 000 events or
// 600 000 telegram-processor RAM accesses, after finishing the picosecond it is in (so the
// cut is clean); B and C run the same operations up to the same operation and simulated
// time. B may need more events than A (it books every hop); past 10x A's budget it stops
// and is not compared.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/register_map.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/settled_line.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/ring/ring.hpp"
#include "sercon/ring/rs485_bus.hpp"
#include "sercon/sim/scheduler.hpp"

namespace {

using sercon::chip::Chip;
using sercon::chip::ChipConfig;
using sercon::chip::LineBurst;
using sercon::chip::LineCondition;
using sercon::chip::LineListener;
using sercon::chip::Pin;
using sercon::chip::Variant;
using sercon::sim::Time;

constexpr Time kUs = sercon::sim::kMicrosecond;
constexpr std::size_t kMaxOps = 64;
constexpr std::uint64_t kEventBudget = 60'000;
constexpr std::uint64_t kTpAccessBudget = 600'000;
constexpr std::uint64_t kSamePicosecondLimit = 200'000;

bool trace_on() {
  static const bool on = std::getenv("RING_FUZZ_TRACE") != nullptr;
  return on;
}

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "invariant violated: %s\n", what.c_str());
  std::abort();
}

void check(bool ok, const std::string& what) {
  if (!ok) violated(what);
}

// --- the input ----------------------------------------------------------------------------

struct NodeSetup {
  ChipConfig config;
};

struct Setup {
  bool bus = false;
  std::vector<NodeSetup> nodes;  // node 0: the master
  std::vector<double> fibre_lengths_m;
  Time bus_delay = 0;
  bool bring_up = false;   // a driver's bring-up: lines on, timing, CP4 lists
  std::uint16_t rate = 0;  // SERMODE rate bits written by the bring-up
  std::uint16_t tscyc = 250;
  bool lazy_initially = true;
  int warm_up_cycles = 0;  // a long step before the operations (bring-up only)
};

enum class OpKind : std::uint8_t {
  RegWrite,
  RegReadAll,
  RamWord,
  RamItem,
  RamList,
  FibreBreak,
  FibreRestore,
  FibreBreakAt,
  FibreRestoreAt,
  BitErrors,
  LazyHops,
  TxdOff,
  TxdOn,
  SwitchOnLines,
  ShortStep,
  LongStep,
  TinyStep,
  kCount,
};

struct Op {
  OpKind kind{};
  std::size_t node = 0;
  std::uint16_t address = 0;
  std::uint16_t value = 0;
  std::uint64_t seed = 0;
  Time time = 0;
  double p = 0;
  std::vector<std::uint16_t> words;  // RamItem / RamList: the words from `address` on
};

ChipConfig fuzzed_config(FuzzedDataProvider& in) {
  static constexpr std::int64_t kMclk[] = {32'000'000, 16'000'000, 20'000'000, 25'000'000,
                                           40'000'000, 50'000'000, 64'000'000, 12'500'000};
  ChipConfig c;
  c.variant = in.ConsumeIntegralInRange(0, 3) == 3 ? Variant::Sercon410B : Variant::Sercon816;
  const auto m = in.ConsumeIntegralInRange<std::size_t>(0, 11);
  c.mclk_hz = kMclk[m < std::size(kMclk) ? m : 0];  // mostly 32 MHz
  c.sbaud = in.ConsumeBool();
  c.sbaud16 = c.variant == Variant::Sercon410B || in.ConsumeBool();
  c.tm0 = in.ConsumeBool();
  c.tm1 = in.ConsumeBool();
  return c;
}

std::uint16_t pick(FuzzedDataProvider& in, std::initializer_list<std::uint16_t> values) {
  const auto i = in.ConsumeIntegralInRange<std::size_t>(0, values.size() - 1);
  return *(values.begin() + i);
}

// Register addresses and values that act, mostly; sometimes anything.
void fuzzed_register_write(FuzzedDataProvider& in, Op& op) {
  static constexpr std::uint16_t kActive[] = {0x01, 0x01, 0x02, 0x02, 0x03, 0x03, 0x04, 0x0A, 0x0A,
                                              0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x10, 0x13, 0x14, 0x15,
                                              0x16, 0x18, 0x19, 0x1C, 0x20, 0x28, 0x29, 0x2A};
  const auto i = in.ConsumeIntegralInRange<std::size_t>(0, std::size(kActive));
  op.address =
      i < std::size(kActive) ? kActive[i] : in.ConsumeIntegralInRange<std::uint16_t>(0, 0x3F);
  if (in.ConsumeIntegralInRange(0, 5) == 0) {
    op.value = in.ConsumeIntegral<std::uint16_t>();
    return;
  }
  switch (op.address) {
    case 0x01: {  // SERMODE: REPON, REGMODE, rates, PRESYNC, POLTXD, SWRST
      std::uint16_t v = 0;
      if (in.ConsumeBool()) v |= 0x0008;  // REPON
      if (in.ConsumeBool()) v |= 0x0020;  // REGMODE
      v |= pick(in, {0x0000, 0x0400, 0x0440, 0x8400, 0x8440});
      if (in.ConsumeIntegralInRange(0, 7) == 0) v |= 0x0100;   // PRESYNC
      if (in.ConsumeIntegralInRange(0, 7) == 0) v |= 0x0200;   // POLTXD
      if (in.ConsumeIntegralInRange(0, 7) == 0) v |= 0x0080;   // POLRXD
      if (in.ConsumeIntegralInRange(0, 15) == 0) v |= 0x0002;  // SWRST
      op.value = v;
      return;
    }
    case 0x02: {  // SERCTRL: TXOE, TXLIGHT, LEDIST/LEMISS, test modes
      std::uint16_t v = pick(in, {0x0041, 0x0041, 0x007F, 0x0000, 0x0001, 0x0040, 0x0043});
      if (in.ConsumeIntegralInRange(0, 3) == 0)
        v |= static_cast<std::uint16_t>(in.ConsumeIntegralInRange(0, 7) << 9);
      if (in.ConsumeBool()) v |= pick(in, {0x0080, 0x0100, 0x0180});
      op.value = v;
      return;
    }
    case 0x03:
      op.value = pick(in, {0x0100, 0x0000, 0x0106, 0x0101});
      return;
    case 0x04:
      op.value = pick(in, {0xFFFF, 0x0382, 0x0004, 0x0020});
      return;
    case 0x0A:
      op.value = in.ConsumeIntegralInRange<std::uint16_t>(0, 7);
      return;
    case 0x0B:
      op.value = in.ConsumeIntegral<std::uint16_t>() & 0x1F1F;
      return;
    case 0x0C:
      op.value = in.ConsumeIntegralInRange<std::uint16_t>(0, 3);
      return;
    case 0x0D:
      op.value = pick(in, {0xFF0A, 0x0801, 0x0000, 0x1002, 0xFFFF});
      return;
    case 0x0E:  // MCLKST << 8 | MCLKDIV
      op.value = pick(in, {0x121F, 0x051F, 0x0F0F, 0x0000, 0x0101, 0x3F3F, 0x1818});
      return;
    case 0x0F:
    case 0x10:  // cycle times, µs
      op.value = pick(in, {250, 100, 500, 1000, 62, 20, 5, 1, 0, 2000});
      return;
    case 0x13:
    case 0x14:
      op.value = in.ConsumeIntegralInRange<std::uint16_t>(0, 6);
      return;
    case 0x15:
    case 0x16:
    case 0x18:
    case 0x19:
      op.value = pick(in, {0, 1, 2, 3, 5, 6, 8, 10, 20, 0xFFFF});
      return;
    case 0x28:
      op.value = in.ConsumeIntegralInRange<std::uint16_t>(0, 0x1FF);
      return;
    case 0x29:
      op.value = 0x42;
      return;
    default:
      op.value = pick(in, {0, 1, 2, 0x42, 0xFF, 0xFFFF, 10, 100, 250});
      return;
  }
}

// One list item as host software writes it (datasheet 4.2; transmit header: docs/
// telegram-processing.md §1): the header and one container, or an end marker.
std::vector<std::uint16_t> fuzzed_item(FuzzedDataProvider& in, std::uint16_t at,
                                       std::uint16_t next) {
  std::vector<std::uint16_t> w;
  const auto adr = static_cast<std::uint16_t>(
      in.ConsumeBool() ? in.ConsumeIntegralInRange(0, 4) : in.ConsumeIntegral<std::uint8_t>());
  const auto len = in.ConsumeIntegralInRange<std::uint16_t>(0, 8);
  const auto trt = pick(in, {0, 10, 20, 28, 36, 44, 60, 100, 150, 240, 0xFFFF});
  std::uint16_t flags = 0;
  if (in.ConsumeIntegralInRange(0, 3) == 0) flags |= 0x0200;  // DBUF
  if (in.ConsumeIntegralInRange(0, 7) == 0) flags |= 0x0100;  // DMA
  const bool svfl = in.ConsumeIntegralInRange(0, 7) == 0;
  const auto control = [&](std::uint16_t n) {
    return static_cast<std::uint16_t>(0x8000 | (svfl ? 0x0400 : 0) | n);
  };
  switch (in.ConsumeIntegralInRange(0, 4)) {
    case 0:
    case 1: {  // receive header: 0x0000 / 0x0800 (ACHK) / 0x1000 (TCHK) / 0x1800 + ADR
      const auto kind = pick(in, {0x0000, 0x0800, 0x1000, 0x1800, 0x0800});
      const auto body = static_cast<std::uint16_t>(5 + 2 + len * ((flags & 0x0200) ? 2 : 1));
      w = {static_cast<std::uint16_t>(kind | flags | adr), trt, len,
           next != 0 ? next : static_cast<std::uint16_t>(at + body), 0};
      w.push_back(control(len));
      w.push_back(in.ConsumeIntegralInRange<std::uint16_t>(0, 2));  // POS
      break;
    }
    case 2:
    case 3: {  // transmit header: 0x4000 idle / 0x4800 + ADR once / 0x5000 + ADR / 0x50FF
      const auto kind = pick(in, {0x5000, 0x4800, 0x4000, 0x50FF, 0x48FF});
      const auto a = static_cast<std::uint16_t>((kind & 0xFF) != 0 ? 0 : adr);
      const auto body = static_cast<std::uint16_t>(4 + 1 + len * ((flags & 0x0200) ? 2 : 1));
      w = {static_cast<std::uint16_t>(kind | flags | a), trt, len,
           next != 0 ? next : static_cast<std::uint16_t>(at + body)};
      w.push_back(control(len));
      break;
    }
    default:  // end marker
      return {0xC000, pick(in, {240, 200, 100, 50, 10, 0, 0xFFFF})};
  }
  const std::size_t data = (flags & 0x0100) ? 0 : len * ((flags & 0x0200) ? 2u : 1u);
  for (std::size_t i = 0; i < data; ++i) w.push_back(in.ConsumeIntegral<std::uint16_t>());
  return w;
}

Setup fuzzed_setup(FuzzedDataProvider& in) {
  Setup s;
  // The defaults (what an exhausted input gives) make a live ring: a master and a slave
  // brought up, lazy hops on, a few cycles run before the operations.
  s.bus = in.ConsumeIntegralInRange(0, 4) == 4;
  const std::size_t n = s.bus ? in.ConsumeIntegralInRange<std::size_t>(2, 4)
                              : 1 + in.ConsumeIntegralInRange<std::size_t>(1, 3);
  const bool same = in.ConsumeBool();
  for (std::size_t i = 0; i < n; ++i) {
    s.nodes.push_back({i > 0 && same ? s.nodes.front().config : fuzzed_config(in)});
  }
  if (!s.bus) {
    for (std::size_t i = 0; i < n; ++i) {
      s.fibre_lengths_m.push_back(static_cast<double>(pick(in, {1, 1, 0, 5, 20, 40, 100, 250})) +
                                  in.ConsumeIntegralInRange(0, 99) / 100.0);
    }
  } else {
    static constexpr Time kDelays[] = {0, 0, 1000, 20'000, 62'500, 500'000};
    s.bus_delay = kDelays[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kDelays) - 1)];
  }
  s.bring_up = in.ConsumeIntegralInRange(0, 3) != 3;
  s.rate = pick(in, {0x0000, 0x0000, 0x0400, 0x0440, 0x8400, 0x8440});
  s.tscyc = pick(in, {250, 250, 500, 1000, 100, 2000});
  s.lazy_initially = in.ConsumeIntegralInRange(0, 7) != 7;
  s.warm_up_cycles = s.bring_up ? 3 + in.ConsumeIntegralInRange(0, 5) : 0;
  return s;
}

std::vector<Op> fuzzed_ops(FuzzedDataProvider& in, const Setup& s) {
  std::vector<Op> ops;
  const std::size_t n = s.nodes.size();
  if (s.warm_up_cycles > 0) {
    Op warm_up;
    warm_up.kind = OpKind::LongStep;
    warm_up.time = s.warm_up_cycles * s.tscyc * kUs;
    ops.push_back(warm_up);
  }
  while (ops.size() <= kMaxOps && in.remaining_bytes() > 0) {
    Op op;
    op.kind = static_cast<OpKind>(
        in.ConsumeIntegralInRange<int>(0, static_cast<int>(OpKind::kCount) - 1));
    op.node = in.ConsumeIntegralInRange<std::size_t>(0, n - 1);
    const std::uint16_t ram =
        s.nodes[op.node].config.variant == Variant::Sercon410B ? 0x400 : 0x800;
    switch (op.kind) {
      case OpKind::RegWrite:
        fuzzed_register_write(in, op);
        break;
      case OpKind::RamWord:
        op.address = in.ConsumeBool() ? in.ConsumeIntegralInRange<std::uint16_t>(0, 10)
                                      : in.ConsumeIntegralInRange<std::uint16_t>(0, ram - 1);
        op.value = in.ConsumeBool() ? pick(in, {0x0000, 0x0040, 0x7FC, 0x3FC, 0xC000, 0x8003,
                                                0x0800, 0x1000, 0x4000, 0x5000, 0xFFFF})
                                    : in.ConsumeIntegral<std::uint16_t>();
        break;
      case OpKind::RamItem:
        op.address = in.ConsumeIntegralInRange<std::uint16_t>(0, ram - 1);
        op.words = fuzzed_item(in, op.address,
                               in.ConsumeBool() ? 0 : in.ConsumeIntegral<std::uint16_t>() & 0x7FF);
        break;
      case OpKind::RamList: {  // a whole list from `address`, and COMPT0 / COMPT1 to it
        op.address =
            static_cast<std::uint16_t>(in.ConsumeIntegralInRange<std::uint16_t>(11, 0x100));
        op.value = in.ConsumeIntegralInRange<std::uint16_t>(0, 2);  // 0: COMPT0, 1: COMPT1, 2: both
        const auto items = in.ConsumeIntegralInRange(1, 5);
        std::uint16_t at = op.address;
        for (int i = 0; i < items; ++i) {
          auto w = fuzzed_item(in, at, 0);
          if (i + 1 == items && w.front() != 0xC000) {
            w.push_back(0xC000);  // the list's end marker after the last item
            w.push_back(pick(in, {240, 200, 100}));
          }
          op.words.insert(op.words.end(), w.begin(), w.end());
          at = static_cast<std::uint16_t>(op.address + op.words.size());
          if (w.front() == 0xC000) break;
        }
        break;
      }
      case OpKind::FibreBreakAt:
      case OpKind::FibreRestoreAt:
        op.time = in.ConsumeIntegralInRange<Time>(0, 300 * kUs);
        break;
      case OpKind::BitErrors:
        op.p = std::initializer_list<double>{0.0, 1e-4, 1e-3, 1e-2, 0.1, 1.0}
                   .begin()[in.ConsumeIntegralInRange(0, 5)];
        op.seed = in.ConsumeIntegral<std::uint64_t>();
        break;
      case OpKind::LazyHops:
        op.value = in.ConsumeBool();
        break;
      case OpKind::ShortStep:
        op.time = in.ConsumeIntegralInRange<Time>(0, 50 * kUs);
        break;
      case OpKind::LongStep:
        op.time = in.ConsumeIntegralInRange<Time>(0, 2000 * kUs);
        break;
      case OpKind::TinyStep:
        op.time = in.ConsumeIntegralInRange<Time>(0, 200'000);
        break;
      default:
        break;
    }
    ops.push_back(std::move(op));
  }
  return ops;
}

// One operation, every field (RING_FUZZ_TRACE): in the input's dump and as it runs.
void print_op(std::size_t i, const Op& op) {
  std::fprintf(stderr, "op %zu: kind %d node %zu address 0x%x value 0x%x time %lld p %g seed %llu",
               i, static_cast<int>(op.kind), op.node, op.address, op.value,
               static_cast<long long>(op.time), op.p, static_cast<unsigned long long>(op.seed));
  if (!op.words.empty()) {
    std::fprintf(stderr, " words");
    for (std::uint16_t w : op.words) std::fprintf(stderr, " 0x%04x", w);
  }
  std::fprintf(stderr, "\n");
}

// All of an input, enough to write it again as a test (RING_FUZZ_TRACE).
void print_input(const Setup& s, const std::vector<Op>& ops) {
  std::fprintf(stderr, "%s of %zu, bring-up %d, rate 0x%04x, tscyc %u, lazy %d, warm-up %d\n",
               s.bus ? "bus" : "ring", s.nodes.size(), s.bring_up, s.rate, s.tscyc,
               s.lazy_initially, s.warm_up_cycles);
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const ChipConfig& c = s.nodes[i].config;
    std::fprintf(stderr, "node %zu: %s, MCLK %lld Hz, SBAUD %d, SBAUD16 %d, TM0 %d, TM1 %d", i,
                 c.variant == Variant::Sercon410B ? "SERCON410B" : "SERCON816",
                 static_cast<long long>(c.mclk_hz), c.sbaud, c.sbaud16, c.tm0, c.tm1);
    if (!s.bus) std::fprintf(stderr, ", fibre %g m", s.fibre_lengths_m[i]);
    std::fprintf(stderr, "\n");
  }
  if (s.bus) std::fprintf(stderr, "bus delay %lld ps\n", static_cast<long long>(s.bus_delay));
  for (std::size_t i = 0; i < ops.size(); ++i) print_op(i, ops[i]);
}

// --- observations -------------------------------------------------------------------------

// One observed stream: a running hash, and the text when RING_FUZZ_TRACE is set.
struct Stream {
  std::string name;
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  std::uint64_t count = 0;
  std::vector<std::string> text;
  void mix(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      hash ^= (v >> (8 * i)) & 0xFF;
      hash *= 0x100000001b3ULL;
    }
  }
  void add(std::initializer_list<std::int64_t> values, const char* what) {
    ++count;
    for (auto v : values) mix(static_cast<std::uint64_t>(v));
    if (trace_on()) {
      std::string s = what;
      for (auto v : values) s += ' ' + std::to_string(v);
      text.push_back(std::move(s));
    }
  }
};

std::uint64_t hash_bits(const LineBurst& b) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  const auto& bits = *b.bits;
  for (std::size_t i = 0; i < bits.size(); ++i) {
    h ^= bits[i] ? 1u : 0u;
    h *= 0x100000001b3ULL;
  }
  return h ^ bits.size();
}

// Takes each change of a line when it happens (behind a SettledLine).
class LineLog final : public LineListener {
 public:
  LineLog(sercon::sim::Scheduler& s, Stream& stream, const bool& closed)
      : s_(s), stream_(stream), closed_(closed) {}
  void line_condition(Time at, LineCondition c, Time period) override {
    if (closed_) return;
    stream_.add({s_.now(), at, static_cast<int>(c), period}, "condition");
  }
  void line_burst(const LineBurst& b) override {
    if (closed_) return;
    stream_.add({s_.now(), b.start, b.bit_period, static_cast<std::int64_t>(b.bits->size()),
                 static_cast<std::int64_t>(hash_bits(b))},
                "burst");
  }

 private:
  sercon::sim::Scheduler& s_;
  Stream& stream_;
  const bool& closed_;  // the run is over: its streams are handed out
};

// Sits between a line's source and its listener and logs what really happens on it. A lazy
// hop through it (line.hpp pass_through) is passed on to the listener's pass_through and,
// when taken, logged as line_burst would log it: the tap changes nothing of the ring.
class Tap final : public LineListener {
 public:
  Tap(sercon::sim::Scheduler& s, Stream& stream, const bool& closed, LineListener& to)
      : log_(s, stream, closed), settled_(s, log_), to_(to) {}
  void line_condition(Time at, LineCondition c, Time period) override {
    settled_.line_condition(at, c, period);
    to_.line_condition(at, c, period);
  }
  void line_burst(const LineBurst& b) override {
    settled_.line_burst(b);
    to_.line_burst(b);
  }
  bool pass_through(const LineBurst& b, LineListener*& next, const LineBurst*& out,
                    sercon::chip::PassedBursts& sender) override {
    const LineBurst copy = b;  // `b` may live where the listener books it
    if (!to_.pass_through(b, next, out, sender)) return false;
    settled_.line_burst(copy);
    return true;
  }
  void book_passed(const LineBurst& b) override { to_.book_passed(b); }

 private:
  LineLog log_;
  sercon::chip::SettledLine settled_;
  LineListener& to_;
};

// --- the simulation -------------------------------------------------------------------------

struct Outcome {
  std::deque<Stream> streams;
  std::uint64_t events = 0;
  std::size_t ops_done = 0;     // ops run whole
  std::optional<Time> cut;      // the budget ran out in op ops_done at this time
  bool circled = false;         // the documented depth-guard exception
  bool over_limit = false;      // run B past its event limit
  std::uint64_t lazy_hops = 0;  // taken by all chips
};

class Sim {
 public:
  Sim(const Setup& setup, bool lazy_allowed) : setup_(setup), lazy_allowed_(lazy_allowed) {
    std::vector<ChipConfig> configs;
    for (const auto& n : setup.nodes) configs.push_back(n.config);
    const std::size_t n = configs.size();
    if (!setup.bus) {
      sercon::ring::RingOptions o;
      o.fibre_lengths_m = setup.fibre_lengths_m;
      ring_ = std::make_unique<sercon::ring::Ring>(
          s_, configs.front(), std::vector<ChipConfig>(configs.begin() + 1, configs.end()), o);
      for (std::size_t i = 0; i < n; ++i) chips_.push_back(&ring_->node(i));
      for (std::size_t i = 0; i < n; ++i) {
        // TxD1 -> tap -> fibre input; fibre output -> tap -> next RxD.
        auto& fibre = ring_->fibre(i);
        taps_.push_back(std::make_unique<Tap>(s_, stream("txd1 of " + std::to_string(i)), closed_,
                                              fibre.input()));
        ring_->serial(i).connect_txd(1, *taps_.back());
        taps_.push_back(std::make_unique<Tap>(s_, stream("rxd of " + std::to_string((i + 1) % n)),
                                              closed_, ring_->serial((i + 1) % n).rxd()));
        fibre.connect(*taps_.back());
      }
    } else {
      bus_ = std::make_unique<sercon::ring::Rs485Bus>(s_, setup.bus_delay);
      bus_log_ = std::make_unique<LineLog>(s_, stream("bus"), closed_);
      bus_settled_ = std::make_unique<sercon::chip::SettledLine>(s_, *bus_log_);
      for (std::size_t i = 0; i < n; ++i) {
        own_.push_back(std::make_unique<Chip>(s_, configs[i]));
        chips_.push_back(own_.back().get());
        bus_nodes_.push_back(bus_->attach(serial(i)));
      }
      bus_->add_node(*bus_settled_);
    }
    static constexpr Pin kPins[] = {
        Pin::INT0,    Pin::INT1,    Pin::BUSYN,   Pin::L_ERRN,  Pin::IDLE, Pin::WDOGN, Pin::CYC_CLK,
        Pin::CON_CLK, Pin::DIV_CLK, Pin::DMAREQR, Pin::DMAREQT, Pin::TxD1, Pin::TxD2};
    for (std::size_t i = 0; i < n; ++i) {
      serial(i).set_lazy_hops(lazy_allowed_ && setup.lazy_initially);
      for (const Pin p : kPins) {
        Stream& st =
            stream("node " + std::to_string(i) + " " + std::string(sercon::chip::pin_name(p)));
        chips_[i]->pin(p).watch([this, &st](sercon::sim::Level level) {
          if (closed_) return;
          st.add({s_.now(), static_cast<int>(level)}, "level");
        });
      }
      ram_streams_.push_back(&stream("ram of " + std::to_string(i)));
      reg_streams_.push_back(&stream("registers of " + std::to_string(i)));
    }
  }

  ~Sim() {
    // The taps on the TxD side forward to fibres the ring destroys before its chips: take
    // the chips' TxD1 off them first (each tells its tap Dark, which the fibre passes on).
    if (ring_) {
      try {
        for (std::size_t i = 0; i < chips_.size(); ++i) ring_->serial(i).disconnect_txd(1);
      } catch (const std::exception&) {
      }
    }
  }

  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  sercon::chip::SerialUnit& serial(std::size_t i) {
    return *chips_[i]->unit<sercon::chip::SerialUnit>();
  }

  // Runs the ops. `stop_at_op` / `stop_time`: where run A's budget ran out (B and C stop
  // there); `event_limit`: the hard limit of this run.
  Outcome run(const std::vector<Op>& ops, std::optional<std::size_t> stop_at_op,
              std::optional<Time> stop_time, std::uint64_t event_limit, bool budgeted) {
    Outcome out;
    try {
      bring_up();
      std::size_t i = 0;
      for (; i < ops.size(); ++i) {
        if (stop_at_op && i == *stop_at_op) {
          // Run A's budget ran out inside this op, at stop_time.
          step_to(*stop_time, event_limit, false, out);
          break;
        }
        if (trace_on()) print_op(i, ops[i]);
        if (!one(ops[i], event_limit, budgeted, out)) break;
        if (trace_on()) {
          std::string sermode;
          for (Chip* c : chips_) sermode += " " + std::to_string(c->regs().value(0x01));
          std::fprintf(stderr, "  -> now %lld ps, SERMODE%s\n", static_cast<long long>(s_.now()),
                       sermode.c_str());
        }
      }
      out.ops_done = i;
      finish();
    } catch (const std::runtime_error& e) {
      if (every_node_repeated_ && std::strstr(e.what(), "circle a ring where every node repeats")) {
        out.circled = true;
      } else {
        std::string repon;
        for (Chip* c : chips_) repon += std::to_string(c->regs().value(0x01)) + " ";
        violated(std::string("exception: ") + e.what() + " (REPON now " + repon +
                 (every_node_repeated_ ? ", all were on" : ", never all on") + ")");
      }
    } catch (const std::exception& e) {
      violated(std::string("exception: ") + e.what());
    }
    out.events = events_;
    for (std::size_t i = 0; i < chips_.size(); ++i) out.lazy_hops += serial(i).lazy_hops_taken();
    if (std::getenv("RING_FUZZ_STATS") != nullptr) {
      std::fprintf(stderr,
                   "%s: %zu nodes, %zu ops done of %zu, %llu events, %llu telegram-processor RAM "
                   "accesses, %.1f us%s\n",
                   bus_ ? "bus" : "ring", chips_.size(), out.ops_done, ops.size(),
                   static_cast<unsigned long long>(events_),
                   static_cast<unsigned long long>(tp_accesses()),
                   static_cast<double>(s_.now()) / kUs, out.cut ? " (cut)" : "");
      for (std::size_t i = 0; i < chips_.size(); ++i) {
        std::fprintf(stderr,
                     "  node %zu: lazy hops %llu, INTSTAT 0x%04x, PHASE 0x%04x, NMSTERR %u\n", i,
                     static_cast<unsigned long long>(serial(i).lazy_hops_taken()),
                     chips_[i]->regs().value(0x04), chips_[i]->regs().value(0x0A),
                     chips_[i]->ram().contents()[10]);
      }
      for (const Stream& st : streams_) {
        if (st.count > 1)
          std::fprintf(stderr, "  %s: %llu\n", st.name.c_str(),
                       static_cast<unsigned long long>(st.count));
      }
    }
    closed_ = true;
    out.streams = std::move(streams_);
    streams_.clear();
    return out;
  }

 private:
  Stream& stream(std::string name) {
    Stream st;
    st.name = std::move(name);
    streams_.push_back(std::move(st));
    return streams_.back();
  }

  void note_repeaters() {
    if (bus_) return;
    for (Chip* c : chips_) {
      if ((c->regs().value(0x01) & 0x0008) == 0) return;
    }
    every_node_repeated_ = true;
  }

  // A driver's bring-up, through registers and DPRAM only (tests/chip/cp4_ring.hpp does
  // the same for the benchmark ring): master + slaves in CP4, an AT per slave, an MDT.
  void bring_up() {
    note_repeaters();
    if (!setup_.bring_up) return;
    s_.run_until(2'222'222);  // out of reset
    const std::size_t n = chips_.size();
    const auto slaves = static_cast<std::uint16_t>(n - 1);
    for (std::size_t i = 0; i < n; ++i) {
      Chip& c = *chips_[i];
      const bool master = i == 0;
      const std::uint16_t repon = master || bus_ ? 0 : 0x0008;
      const std::uint16_t mhz = static_cast<std::uint16_t>(c.config().mclk_hz / 1'000'000);
      c.reg_write(0x01, static_cast<std::uint16_t>(setup_.rate | repon));
      c.reg_write(0x02, 0x0041);
      c.reg_write(0x0E, static_cast<std::uint16_t>(18 << 8 | (mhz - 1)));
      c.reg_write(0x0F, setup_.tscyc);
      c.reg_write(0x10, setup_.tscyc);
      c.reg_write(0x13, 1);
      const std::uint16_t end0 = c.variant() == Variant::Sercon410B ? 0x3FC : 0x7FC;
      const auto tend = static_cast<std::uint16_t>(setup_.tscyc - 10);
      std::vector<std::uint16_t> w;
      const auto put = [&](std::uint16_t at, std::initializer_list<std::uint16_t> v) {
        for (auto x : v) c.ram_write(at++, x);
      };
      put(0, {end0, 0x40});
      put(end0, {0xC000, tend});
      if (!master) {
        c.reg_write(0x15, 0xFFFC);  // JTSCYC1 = TCNTST - 5 (wraps as the tests' does)
        c.reg_write(0x16, 6);
        const auto k = static_cast<std::uint16_t>(i);
        const auto t1 = static_cast<std::uint16_t>(20 + 8 * (k - 1));
        put(0x40, {static_cast<std::uint16_t>(0x5000 | k), t1, 3, 0x48});  // AT
        put(0x44, {0x8003, static_cast<std::uint16_t>(0x0100 | k), 0, 0});
        put(0x48, {0x08FF, 0, static_cast<std::uint16_t>(3 * slaves), 0x52, 0});  // MDT
        put(0x4D, {0x8003, static_cast<std::uint16_t>(3 * (k - 1)), 0, 0, 0});
        put(0x52, {0xC000, tend});
      } else {
        c.reg_write(0x0A, 4);
        std::uint16_t at = 0x40;
        for (std::uint16_t k = 1; k <= slaves; ++k, at += 10) {
          put(at, {static_cast<std::uint16_t>(0x0800 | k), 0, 3,
                   static_cast<std::uint16_t>(at + 10), 0});
          put(static_cast<std::uint16_t>(at + 5), {0x8003, 0, 0, 0, 0});
        }
        const auto t2 = static_cast<std::uint16_t>(20 + 8 * slaves + 12);
        const auto end = static_cast<std::uint16_t>(at + 4 + 4 * slaves);
        put(at, {0x50FF, t2, static_cast<std::uint16_t>(3 * slaves), end});
        for (std::uint16_t k = 1; k <= slaves; ++k) {
          put(static_cast<std::uint16_t>(at + 4 + 4 * (k - 1)),
              {static_cast<std::uint16_t>((k == slaves ? 0x8000 : 0) | 3),
               static_cast<std::uint16_t>(0x0400 | k), 0, 0});
        }
        put(end, {0xC000, tend});
      }
      c.reg_write(0x03, 0x0100);  // ENTMT
    }
    chips_[0]->reg_write(0x01, static_cast<std::uint16_t>(chips_[0]->reg_read(0x01) | 0x0020));
    note_repeaters();
  }

  // Invariant 2: what a register read returns (datasheet 4.1; delta spec 2.11.1.1).
  void check_register(std::size_t node, std::uint16_t address, std::uint16_t value) {
    Chip& c = *chips_[node];
    const std::string where =
        "node " + std::to_string(node) + " register " + std::to_string(address);
    if (address >= sercon::chip::kRegisterCount) {
      check(value == 0, where + ": registers 0x2B..0x3F read 0");
      return;
    }
    const auto masks =
        sercon::chip::register_masks(static_cast<std::uint8_t>(address), c.variant());
    check((value & ~masks.readable) == 0, where + ": unused register bits read 0 (datasheet 4.1)");
    if (address == 0) check(value == sercon::chip::version_of(c.variant()), where + ": VERSION");
  }

  void read_registers(std::size_t node) {
    Stream& st = *reg_streams_[node];
    for (std::uint16_t a = 0; a < 0x40; ++a) {
      const std::uint16_t v = chips_[node]->reg_read(a);
      check_register(node, a, v);
      st.add({s_.now(), a, v}, "reg");
    }
  }

  void observe_ram() {
    for (std::size_t i = 0; i < chips_.size(); ++i) {
      const auto words = chips_[i]->ram().contents();
      Stream& st = *ram_streams_[i];
      std::uint64_t h = 0;
      for (std::size_t a = 0; a < words.size(); ++a) h = (h ^ words[a]) * 0x100000001b3ULL + a;
      st.add({s_.now(), static_cast<std::int64_t>(h)}, "ram");
    }
  }

  void finish() {
    for (std::size_t i = 0; i < chips_.size(); ++i) read_registers(i);
    observe_ram();
    Stream& st = stream("ring");
    if (ring_) {
      for (std::size_t i = 0; i < ring_->fibre_count(); ++i) {
        st.add({static_cast<std::int64_t>(ring_->fibre(i).bit_errors()), ring_->fibre(i).broken()},
               "fibre");
      }
    } else {
      st.add({static_cast<std::int64_t>(bus_->collisions())}, "collisions");
    }
  }

  // Invariant 3: the words the telegram processor may write (docs/telegram-processing.md
  // §1, §2, §4, §5). The walk reads its items one at a time and keeps what it read (a
  // header read before the host rewrote the list stays in force, and a receive header's
  // containers are read at its telegram's detection), so every header the walk could have
  // reached since the simulation began counts, with each DMA / DBUF it had: `seen_` keeps,
  // per chip and word, bit (kind * 4 + DMA * 2 + DBUF) for a header reachable from COMPT0 /
  // COMPT1 at the start of some time step. Empty when structures overlap.
  std::optional<std::vector<bool>> writable_words(std::size_t node) {
    const auto ram = chips_[node]->ram().contents();
    const std::size_t size = ram.size();
    std::vector<std::uint8_t>& seen = seen_[node];
    seen.resize(size, 0);
    enum : std::uint8_t { kHeader0 = 1, kStruct = 2, kWrite = 4 };
    std::vector<std::uint8_t> role(size, 0);
    const auto mark = [&](std::size_t a, std::uint8_t r) {
      if (a < size) role[a] |= r;
    };
    const auto combo = [](std::uint16_t w0) {
      return static_cast<std::uint8_t>(1u << ((w0 >> 14) * 4 + ((w0 >> 8) & 3)));  // DMA: bit 8
    };
    mark(0, kStruct);
    mark(1, kStruct);
    mark(10, kWrite);  // NMSTERR
    std::vector<bool> visited(size, false);
    // The walks start at COMPT0 / COMPT1 and at the next item of every header seen so far
    // (a walk that read a header before the host rewrote the list goes on from the pointer
    // it read then, into the RAM as it is now).
    std::vector<bool>& after = next_[node];
    after.resize(size, false);
    std::vector<std::size_t> starts = {std::size_t{ram[0] & 0x7FFu}, std::size_t{ram[1] & 0x7FFu}};
    for (std::size_t a = 0; a < size; ++a) {
      if (after[a]) starts.push_back(a);
    }
    while (!starts.empty()) {
      const std::size_t start = starts.back();
      starts.pop_back();
      for (std::size_t at = start; at < size && !visited[at];) {
        visited[at] = true;
        const unsigned kind = ram[at] >> 14;
        if (kind == 2) break;
        if (kind == 3) {  // end marker
          mark(at, kStruct);
          mark(at + 1, kStruct);
          break;
        }
        seen[at] |= combo(ram[at]);
        for (std::size_t k = 1; k <= 3; ++k) mark(at + k, kStruct);
        if (at + 3 >= size) break;
        const std::size_t next = ram[at + 3] & 0x7FF;
        if (next < size) after[next] = true;
        at = next;
      }
    }
    for (std::size_t at = 0; at < size; ++at) {
      if (seen[at] == 0) continue;
      // The header as the walk read it then, or as it is now (re-read at the detection).
      if (ram[at] >> 14 < 2) seen[at] |= combo(ram[at]);
      mark(at, kHeader0);
      for (unsigned bits = 0; bits < 8; ++bits) {
        if ((seen[at] & (1u << bits)) == 0) continue;
        const bool receive = bits < 4, dma = (bits & 1) != 0, dbuf = (bits & 2) != 0;
        if (receive) mark(at + 4, kWrite);  // NERR
        std::size_t cont = at + (receive ? 5 : 4);
        for (std::size_t n = 0; cont < size && n < size; ++n) {
          const std::uint16_t control = ram[cont];
          const std::size_t len = control & 0x3FF;
          mark(cont, kStruct);
          std::size_t buffer = cont + 1;
          if (receive) mark(buffer++, kStruct);  // POS
          const std::size_t words = dma ? 0 : (dbuf ? 2 * len : len);
          if (receive) {
            for (std::size_t k = 0; k < words; ++k) mark(buffer + k, kWrite);
          }
          if (control & 0x8000) break;
          cont = buffer + words;
        }
      }
    }
    std::vector<bool> writable(size, false);
    for (std::size_t a = 0; a < size; ++a) {
      const std::uint8_t r = role[a];
      const int roles = (r & kHeader0 ? 1 : 0) + (r & kStruct ? 1 : 0) + (r & kWrite ? 1 : 0);
      if (roles > 1) return std::nullopt;
      writable[a] = (r & (kHeader0 | kWrite)) != 0;
    }
    return writable;
  }

  // Runs events up to `until` (and the rest of the picosecond where a budget runs out).
  // False when a budget ran out (out.cut set) or the hard limit was passed.
  bool step_to(Time until, std::uint64_t event_limit, bool budgeted, Outcome& out) {
    std::vector<std::optional<std::vector<bool>>> writable;
    std::vector<std::vector<std::uint16_t>> before;
    for (std::size_t i = 0; i < chips_.size(); ++i) {
      writable.push_back(writable_words(i));
      before.emplace_back(chips_[i]->ram().contents().begin(), chips_[i]->ram().contents().end());
    }
    bool ok = true;
    for (;;) {
      const auto next = s_.next_time();
      if (!next || *next > until) {
        s_.run_until(until);
        break;
      }
      if (events_ >= event_limit) {
        out.over_limit = true;
        ok = false;
        break;
      }
      if (budgeted && (events_ >= kEventBudget || tp_accesses() > kTpAccessBudget)) {
        // A clean cut: finish this picosecond, so every event up to it has run.
        const Time now = s_.now();
        std::uint64_t same = 0;
        while (s_.next_time() && *s_.next_time() == now) {
          check(++same < kSamePicosecondLimit, "events at one picosecond without end");
          ++events_;
          s_.step();
        }
        out.cut = now;
        ok = false;
        break;
      }
      ++events_;
      s_.step();
    }
    for (std::size_t i = 0; i < chips_.size(); ++i) {
      if (!writable[i]) continue;
      const auto now = chips_[i]->ram().contents();
      for (std::size_t a = 0; a < now.size(); ++a) {
        if (!(*writable[i])[a] && now[a] != before[i][a]) {
          if (trace_on()) {
            for (std::size_t k = 0; k < now.size(); ++k) {
              if (k > 1 && (k + 0x30 < a || k > a + 0x10)) continue;
              std::fprintf(stderr, "  word 0x%03zx: 0x%04x -> 0x%04x%s\n", k, before[i][k], now[k],
                           (*writable[i])[k] ? " (writable)" : "");
            }
          }
          violated("node " + std::to_string(i) + ": DPRAM word " + std::to_string(a) +
                   " changed from " + std::to_string(before[i][a]) + " to " +
                   std::to_string(now[a]) +
                   " in a time step; the telegram processor does not write it "
                   "(docs/telegram-processing.md §1-§5)");
        }
      }
    }
    observe_ram();
    return ok;
  }

  std::uint64_t tp_accesses() const {
    std::uint64_t n = 0;
    for (Chip* c : chips_) n += c->tp_ram_accesses();
    return n;
  }

  bool one(const Op& op, std::uint64_t event_limit, bool budgeted, Outcome& out) {
    Chip& c = *chips_[op.node];
    const Time now = s_.now();
    switch (op.kind) {
      case OpKind::RegWrite: {
        // A write that switches the last repeater on may throw the depth guard's error
        // itself: the telegrams already on the ring start circling within the call.
        const bool before = every_node_repeated_;
        if (op.address == 0x01 && !bus_) {
          bool others = true;
          for (std::size_t i = 0; i < chips_.size(); ++i) {
            if (i != op.node && (chips_[i]->regs().value(0x01) & 0x0008) == 0) others = false;
          }
          every_node_repeated_ = before || others;
        }
        c.reg_write(op.address, op.value);
        every_node_repeated_ = before;
        check_register(op.node, op.address, c.reg_read(op.address));
        note_repeaters();
        break;
      }
      case OpKind::RegReadAll:
        read_registers(op.node);
        break;
      case OpKind::RamWord:
        if (op.address < c.ram().size()) c.ram_write(op.address, op.value);
        break;
      case OpKind::RamItem:
      case OpKind::RamList: {
        std::uint16_t at = op.address;
        for (std::uint16_t w : op.words) {
          if (at >= c.ram().size()) break;
          c.ram_write(at++, w);
        }
        if (op.kind == OpKind::RamList) {
          if (op.value != 1) c.ram_write(0, op.address);
          if (op.value != 0) c.ram_write(1, op.address);
        }
        break;
      }
      case OpKind::FibreBreak:
        if (ring_) ring_->fibre(op.node).break_now();
        break;
      case OpKind::FibreRestore:
        if (ring_) ring_->fibre(op.node).restore();
        break;
      case OpKind::FibreBreakAt:
        if (ring_) ring_->fibre(op.node).break_at(now + op.time);
        break;
      case OpKind::FibreRestoreAt:
        if (ring_) ring_->fibre(op.node).restore_at(now + op.time);
        break;
      case OpKind::BitErrors:
        if (ring_) ring_->fibre(op.node).set_bit_error_rate(op.p, op.seed);
        break;
      case OpKind::LazyHops:
        if (lazy_allowed_) serial(op.node).set_lazy_hops(op.value != 0);
        break;
      case OpKind::TxdOff:
        if (bus_) serial(op.node).disconnect_txd(1);
        break;
      case OpKind::TxdOn:
        if (bus_) serial(op.node).connect_txd(1, bus_->driver(bus_nodes_[op.node]));
        break;
      case OpKind::SwitchOnLines:
        if (ring_) ring_->switch_on_lines();
        note_repeaters();
        break;
      case OpKind::ShortStep:
      case OpKind::LongStep:
      case OpKind::TinyStep:
        return step_to(now + op.time, event_limit, budgeted, out);
      case OpKind::kCount:
        break;
    }
    return true;
  }

  const Setup& setup_;
  bool lazy_allowed_;
  sercon::sim::Scheduler s_;
  std::deque<Stream> streams_;  // stable: watchers and taps keep references
  std::vector<Stream*> ram_streams_, reg_streams_;
  std::unique_ptr<LineLog> bus_log_;
  std::unique_ptr<sercon::chip::SettledLine> bus_settled_;
  std::vector<std::unique_ptr<Tap>> taps_;
  std::unique_ptr<sercon::ring::Rs485Bus> bus_;
  std::vector<std::unique_ptr<Chip>> own_;  // bus nodes
  std::unique_ptr<sercon::ring::Ring> ring_;
  std::vector<Chip*> chips_;
  std::vector<std::size_t> bus_nodes_;
  std::vector<std::vector<std::uint8_t>> seen_ = std::vector<std::vector<std::uint8_t>>(4);
  std::vector<std::vector<bool>> next_ = std::vector<std::vector<bool>>(4);
  std::uint64_t events_ = 0;
  bool every_node_repeated_ = false;
  bool closed_ = false;
};

void compare(const Outcome& a, const Outcome& b, const char* what) {
  check(a.streams.size() == b.streams.size(), std::string(what) + ": stream count");
  for (std::size_t i = 0; i < a.streams.size(); ++i) {
    const Stream& x = a.streams[i];
    const Stream& y = b.streams[i];
    if (x.hash == y.hash && x.count == y.count) continue;
    std::fprintf(stderr, "%s: stream '%s' differs (%llu vs %llu entries)\n", what, x.name.c_str(),
                 static_cast<unsigned long long>(x.count),
                 static_cast<unsigned long long>(y.count));
    for (std::size_t k = 0; k < std::max(x.text.size(), y.text.size()); ++k) {
      const std::string l = k < x.text.size() ? x.text[k] : "-";
      const std::string r = k < y.text.size() ? y.text[k] : "-";
      if (l != r) {
        std::fprintf(stderr, "  first difference at entry %zu:\n    %s\n    %s\n", k, l.c_str(),
                     r.c_str());
        break;
      }
    }
    violated(what);
  }
}

// What the runs came to, printed at exit (campaign figures for docs/fuzzing.md).
struct Tally {
  std::uint64_t inputs = 0, compared = 0, circled = 0, over_limit = 0, lazy_inputs = 0;
  Tally() {
    std::atexit([] {
      const Tally& t = tally();
      std::fprintf(stderr,
                   "ring_fuzz: %llu inputs, %llu compared lazy / not lazy (%llu of them took lazy "
                   "hops), %llu ended by the depth guard, %llu not compared (run B past its "
                   "event limit)\n",
                   static_cast<unsigned long long>(t.inputs),
                   static_cast<unsigned long long>(t.compared),
                   static_cast<unsigned long long>(t.lazy_inputs),
                   static_cast<unsigned long long>(t.circled),
                   static_cast<unsigned long long>(t.over_limit));
    });
  }
  static Tally& tally() {
    static Tally t;
    return t;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const Setup setup = fuzzed_setup(in);
  const std::vector<Op> ops = fuzzed_ops(in, setup);
  if (trace_on()) print_input(setup, ops);
  const std::uint64_t hard_limit = 10 * kEventBudget + kSamePicosecondLimit;

  Outcome a;
  {
    Sim sim(setup, true);
    a = sim.run(ops, std::nullopt, std::nullopt, hard_limit, true);
  }
  std::optional<std::size_t> stop_op;
  if (a.cut) stop_op = a.ops_done;
  Tally& tally = Tally::tally();
  ++tally.inputs;
  if (a.circled) {  // the documented exception: where it comes depends on bookings
    ++tally.circled;
    return 0;
  }
  Outcome c;
  {
    Sim sim(setup, true);
    c = sim.run(ops, stop_op, a.cut, hard_limit, false);
  }
  check(!c.circled, "determinism: run C threw where run A did not");
  check(c.events == a.events, "determinism: runs A and C ran " + std::to_string(a.events) +
                                  " and " + std::to_string(c.events) + " events");
  compare(a, c, "determinism: runs A and C (the same input twice) differ");
  Outcome b;
  {
    Sim sim(setup, false);
    b = sim.run(ops, stop_op, a.cut, hard_limit, false);
  }
  if (b.circled || b.over_limit) {
    ++(b.circled ? tally.circled : tally.over_limit);
    return 0;
  }
  compare(a, b, "lazy hops: runs A (lazy) and B (no lazy hops) differ");
  ++tally.compared;
  if (a.lazy_hops > 0) ++tally.lazy_inputs;
  return 0;
}
