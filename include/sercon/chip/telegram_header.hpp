// The DPRAM words the telegram processor walks (datasheet 4.2, sercos-facts §5;
// docs/telegram-processing.md, "DPRAM structures"). Pure decoding: no RAM access here.
//
//   fixed words     0 COMPT0, 1 COMPT1, 2..9 SCPT0..7, 10 NMSTERR
//   receive header  5 words: word0 (kind 00), TRT, TLEN, PT, NERR          (datasheet 4.2.1)
//   transmit header 4 words: word0 (kind 01), TRT, TLEN, PT                 (project, facts §5)
//   end marker      2 words: word0 (kind 11), TEND                          (datasheet 4.2.3)
//   data container  receive: control word + POS; transmit: control word     (datasheet 4.2.2)
#pragma once

#include <cstdint>

namespace sercon::chip::telegram {

// Fixed RAM words (datasheet 4.2).
inline constexpr std::uint16_t kCompt0 = 0;  // list for phases 0..2
inline constexpr std::uint16_t kCompt1 = 1;  // list for phases 3..4
inline constexpr std::uint16_t kScpt0 = 2;   // SCPT0..7 at 2..9
inline constexpr std::uint16_t kNmsterr = 10;

// List pointers (COMPTn, PT) are word addresses in bits 0..10 (datasheet 4.2.1, PT).
inline constexpr std::uint16_t kPointerMask = 0x07FF;
constexpr std::uint16_t pointer(std::uint16_t word) {
  return static_cast<std::uint16_t>(word & kPointerMask);
}

enum class Kind : std::uint8_t {
  Receive,    // bits 15..14 = 00
  Transmit,   // 01
  Invalid,    // 10: no structure has it; the list stops (a list fault)
  EndMarker,  // 11
};

constexpr Kind kind_of(std::uint16_t word0) {
  switch (word0 >> 14) {
    case 0:
      return Kind::Receive;
    case 1:
      return Kind::Transmit;
    case 2:
      return Kind::Invalid;
    default:
      return Kind::EndMarker;
  }
}

// Word 0 bits shared by receive and transmit headers (datasheet 4.2.1).
inline constexpr std::uint16_t kAdrMask = 0x00FF;
inline constexpr std::uint16_t kDma = 1u << 8;
inline constexpr std::uint16_t kDbuf = 1u << 9;
inline constexpr std::uint16_t kVal = 1u << 10;
// Receive header only.
inline constexpr std::uint16_t kAchk = 1u << 11;
inline constexpr std::uint16_t kTchk = 1u << 12;
inline constexpr std::uint16_t kRerr = 1u << 13;
// Transmit header only (sercos-facts §5 values 0x4000 / 0x4800+a / 0x5000+a; project names).
inline constexpr std::uint16_t kEn = 1u << 11;    // send once; written back as 0 at the start
inline constexpr std::uint16_t kCycl = 1u << 12;  // send in every cycle

// Word offsets inside the structures.
inline constexpr std::uint16_t kTimeWord = 1;    // TRT / TEND
inline constexpr std::uint16_t kLengthWord = 2;  // TLEN
inline constexpr std::uint16_t kNextWord = 3;    // PT
inline constexpr std::uint16_t kNerrWord = 4;    // receive headers only
inline constexpr std::uint16_t kReceiveHeaderWords = 5;
inline constexpr std::uint16_t kTransmitHeaderWords = 4;
inline constexpr std::uint16_t kEndMarkerWords = 2;

// The data-storage mode of a telegram (word 0 bits 8, 9).
struct Storage {
  bool dma = false;
  bool dbuf = false;

  // Data words a container of `len` words occupies after its control words: none with
  // DMA, two buffers with double buffering.
  constexpr std::uint32_t buffer_words(std::uint32_t len) const {
    return dma ? 0 : (dbuf ? 2 * len : len);
  }
};

constexpr Storage storage_of(std::uint16_t word0) {
  return Storage{(word0 & kDma) != 0, (word0 & kDbuf) != 0};
}

// Data container control word 0 (datasheet 4.2.2).
struct Container {
  std::uint16_t len = 0;  // data words, 0..1023
  bool svfl = false;      // uses service container `nsv`
  std::uint8_t nsv = 0;   // 0..7
  bool scmaster = false;  // service container in master (1) or slave (0) coding
  bool lastdc = false;    // last container of the telegram
};

// Single fields of a control word, for loops that test them in place.
constexpr std::uint16_t container_len(std::uint16_t control) {
  return static_cast<std::uint16_t>(control & 0x03FF);
}
constexpr bool container_svfl(std::uint16_t control) { return (control & (1u << 10)) != 0; }
constexpr bool container_lastdc(std::uint16_t control) { return (control & (1u << 15)) != 0; }

constexpr Container container_of(std::uint16_t control) {
  Container c;
  c.len = container_len(control);
  c.svfl = container_svfl(control);
  c.nsv = static_cast<std::uint8_t>((control >> 11) & 0x7);
  c.scmaster = (control & (1u << 14)) != 0;
  c.lastdc = container_lastdc(control);
  return c;
}

// Control words in front of a container's data: receive containers carry POS as well.
inline constexpr std::uint16_t kReceiveContainerWords = 2;
inline constexpr std::uint16_t kTransmitContainerWords = 1;

}  // namespace sercon::chip::telegram
