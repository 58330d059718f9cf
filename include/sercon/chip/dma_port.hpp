// The DMA interface (datasheet Table 1 DMAREQR/DMAACKRN/DMAREQT/DMAACKTN, 4.2.1 DMA bit;
// docs/telegram-processing.md, "DMA"). Two FIFOs of kDepth words between the telegram
// processor and the µP's DMA controller:
//  - receive: the words of receive containers of telegrams with DMA = 1 enter at the
//    telegram's detection; DMAREQR is high while a word can be read and goes low at the
//    beginning of the read of the last word; a read with DMAACKRN = 0 takes the next word
//    whatever A6-1 and the chip selects say.
//  - transmit: DMAREQT is high while a word can be written and goes low at the beginning of
//    the write that fills the FIFO; a write with DMAACKTN = 0 enters the FIFO; a transmit
//    telegram with DMA = 1 takes its container words from the FIFO at its start.
// DMAREQR/T are MCLK-clocked (datasheet 3.5.1 t_MCLD): a change takes effect at the first
// MCLK edge at or after its cause, except the drop at the beginning of an access, which
// follows the strobe (3.5.6 t_PRQ). The FIFOs and RXCNT / TXCNT change at once.
// Overrun (a word that finds the FIFO full or disabled) and underrun (a word wanted from an
// empty or disabled FIFO) raise INT_DMAERR. DMACTRL (0x0C): DMARXEN / DMATXEN enable (0
// also empties the FIFO), RXCNT / TXCNT count the words held.
// 16-bit bus: one access moves one word, on D15-0 as a RAM word (BYTEDIR = 1 swaps its
// bytes). 8-bit bus: two byte accesses per word, A0 = 0 then A0 = 1 (byte order by BYTEDIR
// as for RAM); the word moves with the A0 = 1 access. acknowledge_read / _write move
// logical words, as the chip's word API does.
#pragma once

#include <cstdint>
#include <span>

#include "sercon/chip/bus.hpp"
#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/dma_fifo.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/tick_alarm.hpp"

namespace sercon::chip {

class Chip;

class DmaPort : public ChipUnit {
 public:
  static constexpr std::size_t kDepth = 16;

  explicit DmaPort(Chip& chip);

  void reset(ResetCause cause) override;

  // --- telegram processor's side ------------------------------------------------------
  // Received container words into the receive FIFO; those that do not fit are lost
  // (overrun).
  void receive(std::span<const std::uint16_t> words);
  // Fills `words` from the transmit FIFO; words it cannot supply are 0 (underrun).
  void transmit(std::span<std::uint16_t> words);

  // --- DMA controller's side: one whole acknowledge cycle, as the pins would make it ---
  // A read with DMAACKRN = 0: the next word (0xFFFF, the floating bus, on underrun).
  std::uint16_t acknowledge_read();
  // A write with DMAACKTN = 0.
  void acknowledge_write(std::uint16_t word);

  std::size_t receive_count() const { return rx_.size(); }
  std::size_t transmit_count() const { return tx_.size(); }

 private:
  // One access to a FIFO. `completes`: the access moves the word (16-bit bus, or the
  // A0 = 1 byte on an 8-bit bus).
  bool read_word(bool completes, std::uint16_t& word);
  void begin_write(bool completes);
  void end_write(bool completes, std::uint16_t bits, std::uint16_t mask);

  BusStrobes strobes() const;
  ByteLanes lanes(bool bus16, unsigned a0) const;  // as for RAM; a0 on an 8-bit bus only
  unsigned address_a0() const;
  void on_strobe_pin();
  void read_starts();
  void read_ends();
  void write_starts();
  void write_ends();
  bool rx_enabled() const { return rx_enable_.on(regs_); }
  bool tx_enabled() const { return tx_enable_.on(regs_); }
  void on_control_write(std::uint16_t before);
  // What caused the FIFO state to change: the beginning of an access (its request drop
  // follows the strobe) or anything else (the requests follow at an MCLK edge).
  enum class Change : std::uint8_t { Clocked, AccessBegins };
  // RXCNT / TXCNT now; DMAREQR/T as `change` says.
  void refresh(Change change = Change::Clocked);
  void drive_requests();  // the pins take reqr_ / reqt_

  Chip& chip_;
  RegisterFile& regs_;
  Interrupts& interrupts_;
  FieldRef rx_enable_, tx_enable_, rx_count_, tx_count_;
  WordFifo<kDepth> rx_;
  WordFifo<kDepth> tx_;
  BusStrobes active_;
  bool rx_word_open_ = false;        // 8-bit bus: the head word's first byte has been read
  std::uint16_t tx_partial_ = 0;     // 8-bit bus: the word being written byte by byte
  bool tx_writing_ = false;          // a write that moves a word has begun
  bool write_acknowledged_ = false;  // DMAACKTN was 0 when the write strobe began
  std::uint16_t driven_ = 0;         // data lines driven for a DMA read in progress

  bool reqr_ = false, reqt_ = false;          // the requests the FIFO state asks for
  bool reqr_out_ = false, reqt_out_ = false;  // the levels on DMAREQR / DMAREQT
  TickAlarm request_edge_;                    // the MCLK edge that drives them
};

}  // namespace sercon::chip
