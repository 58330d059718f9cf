// A SERCOS ring in CP4 at 16 Mbit/s, set up through registers and DPRAM only (the host
// helpers of telegram_bench.hpp): master + N slaves on a ring::Ring (1 m fibres, repeaters
// on). Per drive: an AT with status + 2 words, an MDT record of control + 2 words.
// - up to 8 slaves: everything in DPRAM;
// - more: the cycle is computed to fit the ATs and the MDT (layout_for). The master's DPRAM
//   (2048 words) cannot hold 254 receive headers with buffers plus a 762-word MDT, so the
//   master takes the ATs of slaves 2..N through DMA containers (no buffer; its FIFO is off,
//   so those words are dropped: INT_DMAERR) and sends the MDT from a DMA container (FIFO
//   off: zeros go out). The AT of slave 1 still lands in DPRAM, so a data change is checked
//   end to end through all repeaters.
// Used by bench/ring_bench.cpp and the ring tests (docs/performance.md, "Ring").
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/ring/ring.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip::telegram_testing {

constexpr std::uint16_t kList = 0x040;
constexpr std::uint16_t kPhase0End = 0x7FC;  // end marker for phases 0..2, above any list
constexpr std::uint16_t kAtWords = 3;        // status + 2 cyclic words
constexpr std::uint16_t kMdtWords = 3;       // control + 2 cyclic words
constexpr std::uint16_t kAtSpacingUs = 8;    // an AT of 3 words is at most ~6.5 µs

// Slave list (addresses): AT transmit header, its container, MDT receive header, its
// container, end marker.
constexpr std::uint16_t kSlaveAt = kList;
constexpr std::uint16_t kSlaveAtData = kSlaveAt + 4 + 1;   // status, d1, d2
constexpr std::uint16_t kSlaveMdt = kSlaveAt + 4 + 1 + 3;  // receive header
constexpr std::uint16_t kSlaveMdtData = kSlaveMdt + 5 + 2;
constexpr std::uint16_t kSlaveEnd = kSlaveMdt + 5 + 2 + 3;

inline std::uint16_t t1_of(std::size_t k) {
  return static_cast<std::uint16_t>(20 + kAtSpacingUs * (k - 1));
}

// Line time of a telegram of `words` data words, worst-case stuffing (all ones).
inline sim::Time line_time(std::size_t words, const Timing& t) {
  const std::vector<std::uint8_t> ones(2 * words, 0xFF);
  return static_cast<sim::Time>(line_bits(0x01, ones)) * t.bit;
}

inline std::uint16_t ceil_us(sim::Time ps, std::uint16_t grid_us) {
  const sim::Time grid = grid_us * sim::kMicrosecond;
  return static_cast<std::uint16_t>((ps + grid - 1) / grid * grid_us);
}

struct Layout {
  std::size_t slaves;
  std::uint16_t t2;     // the MDT, on the master's counter
  std::uint16_t tscyc;  // the cycle, µs
  bool dma;             // master uses DMA containers (254 slaves)
};

// The last AT leaves slave N at T1_N on its counter; on the master's counter it arrives at
// T1_N + TCYCSTART + MST + detection + ring delay (docs/telegram-processing.md §3), and
// the MDT may start once it is in. The cycle ends after the MDT has passed the whole ring.
inline Layout layout_for(std::size_t slaves, std::uint16_t fixed_cycle_us) {
  const Timing t = timing_16mbit();
  const sim::Time hop = 2 * t.bit + ring::Fibre::kDefaultPsPerMetre + t.bit;  // repeater, 1 m, grid
  const sim::Time ring_delay = static_cast<sim::Time>(slaves + 1) * hop;
  const sim::Time mst = line_time(1, t) + 2 * sim::kMicrosecond;  // MST, TCYCSTART, detection
  const sim::Time last_at_in =
      t1_of(slaves) * sim::kMicrosecond + mst + ring_delay + line_time(kAtWords, t) + 8 * t.bit;
  Layout l{slaves, static_cast<std::uint16_t>(ceil_us(last_at_in, 1) + 2), fixed_cycle_us,
           slaves > 8};
  const sim::Time mdt_end = l.t2 * sim::kMicrosecond + line_time(kMdtWords * slaves, t) +
                            ring_delay + 10 * sim::kMicrosecond;
  const std::uint16_t needed = ceil_us(mdt_end, 50);
  if (l.tscyc == 0) l.tscyc = needed;
  if (l.tscyc < needed) throw std::logic_error("cycle too short for the ring");
  return l;
}

class Cp4Ring {
 public:
  explicit Cp4Ring(const Layout& layout)
      : layout_(layout), ring_(scheduler_, chip::ChipConfig{}, chip::ChipConfig{}, layout.slaves) {
    t_ = timing_16mbit();
    scheduler_.run_until(2'222'222);  // out of reset
    for (std::size_t k = 1; k <= layout_.slaves; ++k) program_slave_list(k);
    program_master_list();
    start_master(ring_.master());
  }

  sim::Scheduler& scheduler() { return scheduler_; }
  ring::Ring& ring() { return ring_; }
  std::uint64_t cycle_ps() const { return std::uint64_t{layout_.tscyc} * sim::kMicrosecond; }
  void run_cycles(std::size_t n) {
    scheduler_.run_until(scheduler_.now() + static_cast<sim::Time>(n * cycle_ps()));
  }

  // New cyclic data from slave 1 and slave N, and to drive 1 and N (DPRAM MDT only).
  void change_data(std::uint16_t v) {
    ring_.slave(1).ram_write(kSlaveAtData + 1, v);
    ring_.slave(layout_.slaves).ram_write(kSlaveAtData + 2, static_cast<std::uint16_t>(~v));
    if (!layout_.dma) {
      ring_.master().ram_write(mdt_data(1) + 1, v);
      ring_.master().ram_write(mdt_data(layout_.slaves) + 2, static_cast<std::uint16_t>(~v));
    }
  }
  // Empty when the change arrived everywhere it should; else what is wrong.
  std::string data_arrived(std::uint16_t v) {
    chip::Chip& m = ring_.master();
    if (m.ram_read(at_data(1) + 1) != v) return "slave 1's AT data did not reach the master";
    if (!layout_.dma) {
      if (m.ram_read(at_data(layout_.slaves) + 2) != static_cast<std::uint16_t>(~v))
        return "slave N's AT data did not reach the master";
      if (ring_.slave(1).ram_read(kSlaveMdtData + 1) != v) return "MDT data did not reach slave 1";
      if (ring_.slave(layout_.slaves).ram_read(kSlaveMdtData + 2) != static_cast<std::uint16_t>(~v))
        return "MDT data did not reach slave N";
    }
    return {};
  }
  // Empty when no header anywhere reports an error and every telegram was taken.
  std::string headers_clean() {
    chip::Chip& m = ring_.master();
    for (std::size_t k = 1; k <= layout_.slaves; ++k) {
      const std::uint16_t h = m.ram_read(at_header(k));
      if ((h & 0x2000) != 0 || (h & 0x0400) == 0 || m.ram_read(at_header(k) + 4) != 0)
        return "master: AT " + std::to_string(k) + " RERR/NERR or not valid";
      chip::Chip& s = ring_.slave(k);
      const std::uint16_t r = s.ram_read(kSlaveMdt);
      if ((r & 0x2000) != 0 || (r & 0x0400) == 0 || s.ram_read(kSlaveMdt + 4) != 0)
        return "slave " + std::to_string(k) + ": MDT RERR/NERR or not valid";
      if (s.reg_read(kPhase) >> 8 != 4) return "slave " + std::to_string(k) + " not in CP4";
    }
    if (m.ram_read(10) != 0) return "master NMSTERR";
    return {};
  }

 private:
  // Master list: per slave a receive header (ACHK, any time) + container; then the MDT.
  std::uint16_t at_header(std::size_t k) const {
    if (!layout_.dma) return static_cast<std::uint16_t>(kList + 10 * (k - 1));
    return static_cast<std::uint16_t>(k == 1 ? kList : kList + 10 + 7 * (k - 2));
  }
  std::uint16_t at_data(std::size_t k) const {
    return static_cast<std::uint16_t>(at_header(k) + 7);
  }
  std::uint16_t mdt_header() const { return at_header(layout_.slaves + 1); }
  std::uint16_t mdt_data(std::size_t k) const {
    return static_cast<std::uint16_t>(mdt_header() + 4 + 4 * (k - 1) + 1);
  }

  void program_slave_list(std::size_t k) {
    chip::Chip& s = ring_.slave(k);
    const auto adr = static_cast<std::uint16_t>(k);
    program_slave(s, t_, layout_.tscyc);
    words(s, 0, {kPhase0End, kList});
    transmit_header(s, kSlaveAt, static_cast<std::uint16_t>(0x5000 | adr), t1_of(k), kAtWords,
                    kSlaveMdt);
    words(s, kSlaveAt + 4, {0x8000 | kAtWords, static_cast<std::uint16_t>(0x0100 | adr), 0, 0});
    receive_header(s, kSlaveMdt, 0x08FF, 0, static_cast<std::uint16_t>(kMdtWords * layout_.slaves),
                   kSlaveEnd);
    words(s, kSlaveMdt + 5,
          {0x8000 | kMdtWords, static_cast<std::uint16_t>(kMdtWords * (k - 1)), 0, 0, 0});
    end_marker(s, kSlaveEnd, static_cast<std::uint16_t>(layout_.tscyc - 10));
    end_marker(s, kPhase0End, static_cast<std::uint16_t>(layout_.tscyc - 10));
    enable_transmission(s);
  }

  void program_master_list() {
    chip::Chip& m = ring_.master();
    program_master(m, t_, layout_.tscyc, 4);
    words(m, 0, {kPhase0End, kList});
    for (std::size_t k = 1; k <= layout_.slaves; ++k) {
      const std::uint16_t at = at_header(k);
      const bool dma = layout_.dma && k > 1;
      const auto word0 = static_cast<std::uint16_t>(0x0800 | (dma ? 0x0100 : 0) | k);
      receive_header(m, at, word0, 0, kAtWords, at_header(k + 1));
      if (dma) {
        words(m, at + 5, {0x8000 | kAtWords, 0});
      } else {
        words(m, at + 5, {0x8000 | kAtWords, 0, 0, 0, 0});
      }
    }
    const std::uint16_t mdt = mdt_header();
    const auto mdt_len = static_cast<std::uint16_t>(kMdtWords * layout_.slaves);
    if (layout_.dma) {
      transmit_header(m, mdt, 0x51FF, layout_.t2, mdt_len, static_cast<std::uint16_t>(mdt + 5));
      words(m, mdt + 4, {static_cast<std::uint16_t>(0x8000 | mdt_len)});
      end_marker(m, static_cast<std::uint16_t>(mdt + 5),
                 static_cast<std::uint16_t>(layout_.tscyc - 10));
    } else {
      const auto end = static_cast<std::uint16_t>(mdt + 4 + 4 * layout_.slaves);
      transmit_header(m, mdt, 0x50FF, layout_.t2, mdt_len, end);
      for (std::size_t k = 1; k <= layout_.slaves; ++k) {
        const auto last = static_cast<std::uint16_t>(k == layout_.slaves ? 0x8000 : 0);
        words(m, static_cast<std::uint16_t>(mdt + 4 + 4 * (k - 1)),
              {static_cast<std::uint16_t>(last | kMdtWords), static_cast<std::uint16_t>(0x0400 | k),
               0, 0});
      }
      end_marker(m, end, static_cast<std::uint16_t>(layout_.tscyc - 10));
    }
    end_marker(m, kPhase0End, static_cast<std::uint16_t>(layout_.tscyc - 10));
    enable_transmission(m);
  }

  Layout layout_;
  Timing t_;
  sim::Scheduler scheduler_;
  ring::Ring ring_;
};

}  // namespace sercon::chip::telegram_testing
