#include "sercon/chip/dma_port.hpp"

#include "sercon/chip/pin_bus.hpp"
#include "sercon/chip/required_unit.hpp"

namespace sercon::chip {

DmaPort::DmaPort(Chip& chip)
    : chip_(chip),
      regs_(chip.regs()),
      interrupts_(required_unit<Interrupts>(chip, "DmaPort")),
      rx_enable_(field_ref("DMARXEN", chip.variant())),
      tx_enable_(field_ref("DMATXEN", chip.variant())),
      rx_count_(field_ref("RXCNT", chip.variant())),
      tx_count_(field_ref("TXCNT", chip.variant())),
      request_edge_(chip.scheduler(), chip.mclk(), [this] { drive_requests(); }) {
  for (Pin p : {Pin::RDN, Pin::WRN, Pin::BUSMODE0, Pin::BUSMODE1}) {
    chip_.pin(p).react([this](sim::Level) { on_strobe_pin(); });
  }
  regs_.on_write(rx_enable_.address,
                 [this](std::uint16_t, std::uint16_t before) { on_control_write(before); });
}

void DmaPort::reset(ResetCause) {
  rx_.clear();
  tx_.clear();
  rx_word_open_ = false;
  tx_partial_ = 0;
  tx_writing_ = false;
  write_acknowledged_ = false;  // a write the reset cut short moves nothing when it ends
  read_ends();                  // D15-0 HighZ: a read the reset cut short drives no more
  // The chip has set DMAREQR/T inactive already: a reset does not wait for MCLK.
  request_edge_.cancel();
  reqr_out_ = reqt_out_ = false;
  refresh();
}

// Clearing an enable empties that FIFO: its words belong to a transfer the µP gave up.
void DmaPort::on_control_write(std::uint16_t before) {
  const std::uint16_t now = regs_.value(rx_enable_.address);
  if ((before & rx_enable_.mask) && !(now & rx_enable_.mask)) {
    rx_.clear();
    rx_word_open_ = false;
  }
  if ((before & tx_enable_.mask) && !(now & tx_enable_.mask)) {
    tx_.clear();
    tx_partial_ = 0;
  }
  refresh();
}

void DmaPort::refresh(Change change) {
  rx_count_.put(regs_, static_cast<std::uint16_t>(rx_.size()));
  tx_count_.put(regs_, static_cast<std::uint16_t>(tx_.size()));
  // A word whose read has begun no longer counts as readable; a word whose write has begun
  // already counts as written (Table 1: both requests drop at the beginning of the access).
  const std::size_t readable = rx_.size() - (rx_word_open_ && !rx_.empty() ? 1 : 0);
  const std::size_t claimed = tx_.size() + (tx_writing_ ? 1 : 0);
  reqr_ = rx_enabled() && readable > 0;
  reqt_ = tx_enabled() && claimed < kDepth;
  // Datasheet 3.5.6 t_PRQ: the drop at the beginning of an access follows the strobe.
  if (change == Change::AccessBegins) {
    if (reqr_out_ && !reqr_) {
      reqr_out_ = false;
      chip_.set_output(Pin::DMAREQR, false);
    }
    if (reqt_out_ && !reqt_) {
      reqt_out_ = false;
      chip_.set_output(Pin::DMAREQT, false);
    }
  }
  if (reqr_ == reqr_out_ && reqt_ == reqt_out_) return;
  // Every other change comes with a rising MCLK edge (3.5.1 t_MCLD): the first at or after
  // now. The pins then take the state of that instant.
  const Edge edge = chip_.mclk().first_at_or_after(chip_.scheduler().now());
  if (chip_.mclk().time_of(edge) == chip_.scheduler().now()) {
    request_edge_.cancel();
    drive_requests();
  } else if (!request_edge_.pending()) {
    request_edge_.at_edge(edge);
  }
}

void DmaPort::drive_requests() {
  if (reqr_out_ != reqr_) {
    reqr_out_ = reqr_;
    chip_.set_output(Pin::DMAREQR, reqr_);
  }
  if (reqt_out_ != reqt_) {
    reqt_out_ = reqt_;
    chip_.set_output(Pin::DMAREQT, reqt_);
  }
}

// --- telegram processor's side ----------------------------------------------------------

void DmaPort::receive(std::span<const std::uint16_t> words) {
  bool lost = false;
  for (std::uint16_t w : words) lost |= !(rx_enabled() && rx_.push(w));
  if (lost) interrupts_.raise(Irq::DmaErr);
  refresh();
}

void DmaPort::transmit(std::span<std::uint16_t> words) {
  bool missing = false;
  for (std::uint16_t& w : words) {
    if (!(tx_enabled() && tx_.pop(w))) {
      w = 0;
      missing = true;
    }
  }
  if (missing) interrupts_.raise(Irq::DmaErr);
  refresh();
}

// --- accesses -------------------------------------------------------------------------

bool DmaPort::read_word(bool completes, std::uint16_t& word) {
  if (!rx_enabled() || rx_.empty()) {
    interrupts_.raise(Irq::DmaErr);
    rx_word_open_ = false;
    refresh(Change::AccessBegins);
    return false;
  }
  if (completes) {
    rx_.pop(word);
    rx_word_open_ = false;
  } else {
    word = rx_.front();
    rx_word_open_ = true;
  }
  refresh(Change::AccessBegins);
  return true;
}

void DmaPort::begin_write(bool completes) {
  if (!completes) return;
  tx_writing_ = true;
  refresh(Change::AccessBegins);
}

void DmaPort::end_write(bool completes, std::uint16_t bits, std::uint16_t mask) {
  tx_partial_ = static_cast<std::uint16_t>((tx_partial_ & ~mask) | (bits & mask));
  if (!completes) return;  // 8-bit bus: the first byte waits for the second
  tx_writing_ = false;
  if (!(tx_enabled() && tx_.push(tx_partial_))) interrupts_.raise(Irq::DmaErr);
  refresh();
}

std::uint16_t DmaPort::acknowledge_read() {
  std::uint16_t word = 0xFFFF;
  if (chip_.in_reset()) return word;  // held in reset: nothing answers, the bus floats
  if (!chip_.input_high(Pin::BUSWIDTH)) {
    std::uint16_t first = 0;
    read_word(false, first);  // A0 = 0
  }
  return read_word(true, word) ? word : std::uint16_t{0xFFFF};
}

void DmaPort::acknowledge_write(std::uint16_t word) {
  if (chip_.in_reset()) return;
  if (!chip_.input_high(Pin::BUSWIDTH)) {
    const ByteLanes low = lanes(false, 0);
    begin_write(false);
    end_write(false, word, low.word_mask());
    const ByteLanes high = lanes(false, 1);
    begin_write(true);
    end_write(true, word, high.word_mask());
    return;
  }
  begin_write(true);
  end_write(true, word, 0xFFFF);
}

// --- pins -----------------------------------------------------------------------------

// The strobe decoding of the bus interface (datasheet Table 1, BUSMODE0/1, RDN, WRN).
BusStrobes DmaPort::strobes() const {
  return decode_strobes(chip_.input_high(Pin::RDN), chip_.input_high(Pin::WRN),
                        chip_.input_high(Pin::BUSMODE0), chip_.input_high(Pin::BUSMODE1));
}

// The lanes of a RAM access: a 16-bit DMA access is a whole-word access (A0 = 0,
// BHEN = 0), so BYTEDIR = 1 byte-swaps it on D15-0 as it does a RAM word (docs/chip.md
// "Byte lanes").
ByteLanes DmaPort::lanes(bool bus16, unsigned a0) const {
  return byte_lanes(bus16, chip_.input_high(Pin::BYTEDIR),
                    static_cast<std::uint16_t>(bus16 ? 0u : a0), false);
}

unsigned DmaPort::address_a0() const {
  if (chip_.input_high(Pin::ADMUX)) {
    const auto* bus = const_cast<Chip&>(chip_).unit<PinBus>();
    return bus ? (bus->latched_address() & 1u) : 0u;
  }
  return chip_.input_high(Pin::A0) ? 1u : 0u;
}

// Held in reset (RSTN = 0, OUTZ = 1) the port starts no access: like the registers it is
// held, so a DMA controller cycling on meets no FIFO, drives nothing and latches no
// INT_DMAERR (docs/chip.md "Resets"). Ends are still followed; the reset itself released
// D15-0 of a read begun before it.
void DmaPort::on_strobe_pin() {
  const BusStrobes now = strobes();
  if (active_.read && !now.read) read_ends();
  if (active_.write && !now.write) write_ends();
  const bool held = chip_.in_reset();
  const bool read_starts_now = !held && !active_.read && now.read;
  const bool write_starts_now = !held && !active_.write && now.write;
  active_ = now;
  if (read_starts_now) read_starts();
  if (write_starts_now) write_starts();
}

void DmaPort::read_starts() {
  if (chip_.input_high(Pin::DMAACKRN)) return;
  const bool bus16 = chip_.input_high(Pin::BUSWIDTH);
  const unsigned a0 = bus16 ? 1u : address_a0();
  std::uint16_t word = 0;
  if (!read_word(a0 == 1, word)) return;  // underrun: D15-0 float
  const ByteLanes l = lanes(bus16, a0);
  driven_ = l.data_mask();
  const std::uint16_t data = l.to_data(word);
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (driven_ & (1u << bit)) chip_.set_output(data_pin(bit), ((unsigned{data} >> bit) & 1u) != 0);
  }
}

void DmaPort::read_ends() {
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (driven_ & (1u << bit)) chip_.set_output(data_pin(bit), sim::Level::HighZ);
  }
  driven_ = 0;
}

void DmaPort::write_starts() {
  write_acknowledged_ = !chip_.input_high(Pin::DMAACKTN);
  if (!write_acknowledged_) return;
  const bool bus16 = chip_.input_high(Pin::BUSWIDTH);
  begin_write(bus16 || address_a0() == 1);
}

// Data is taken at the end of the strobe, as for register and RAM writes.
void DmaPort::write_ends() {
  const bool acknowledged = write_acknowledged_ && !chip_.input_high(Pin::DMAACKTN);
  write_acknowledged_ = false;
  if (!acknowledged) {
    if (tx_writing_) {
      tx_writing_ = false;
      refresh();
    }
    return;
  }
  std::uint16_t data = 0;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (chip_.input_high(data_pin(bit))) data = static_cast<std::uint16_t>(data | 1u << bit);
  }
  const bool bus16 = chip_.input_high(Pin::BUSWIDTH);
  const unsigned a0 = bus16 ? 1u : address_a0();
  const ByteLanes l = lanes(bus16, a0);
  end_write(a0 == 1, l.to_word(data), l.word_mask());
}

}  // namespace sercon::chip
