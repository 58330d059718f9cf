#include "sercon/chip/pin_bus.hpp"

#include "sercon/chip/chip.hpp"

namespace sercon::chip {

PinBus::PinBus(Chip& chip) : chip_(chip) {
  for (Pin p : {Pin::RDN, Pin::WRN, Pin::BUSMODE0, Pin::BUSMODE1}) {
    chip_.pin(p).react([this](sim::Level) { on_strobe_pin(); });
  }
  for (Pin p : {Pin::ALEL, Pin::ALEH, Pin::ADMUX}) {
    chip_.pin(p).react([this](sim::Level) { on_latch_pin(); });
  }
  for (unsigned bit = 0; bit < 16; ++bit) {
    chip_.pin(data_pin(bit)).react([this](sim::Level) { on_latch_pin(); });
  }
}

void PinBus::reset(ResetCause) {
  // Every reset sets D15-0 HighZ (docs/chip.md "Resets"). A read samples its word when
  // its strobe starts, so a strobe still held drives nothing until a new one begins.
  release_data_lines();
  // The reset released BUSYN: a write in progress reports no collision; and it aborted that
  // write: its end writes nothing (docs/chip.md "Resets", as DmaPort's write).
  write_busy_ = false;
  write_cut_ = active_.write;
}

BusStrobes PinBus::strobes() const {
  return decode_strobes(chip_.input_high(Pin::RDN), chip_.input_high(Pin::WRN),
                        chip_.input_high(Pin::BUSMODE0), chip_.input_high(Pin::BUSMODE1));
}

BusCycle PinBus::sample(bool write) const {
  BusCycle c;
  c.write = write;
  if (chip_.input_high(Pin::ADMUX)) {
    c.address = latch_;
  } else {
    for (unsigned bit = 0; bit < 16; ++bit) {
      if (chip_.input_high(address_pin(bit)))
        c.address = static_cast<std::uint16_t>(c.address | 1u << bit);
    }
  }
  for (unsigned bit = 0; bit < 16 && write; ++bit) {
    if (chip_.input_high(data_pin(bit))) c.data = static_cast<std::uint16_t>(c.data | 1u << bit);
  }
  c.bhen = chip_.input_high(Pin::BHEN);
  c.mcsn0 = chip_.input_high(Pin::MCSN0);
  c.mcsn1 = chip_.input_high(Pin::MCSN1);
  c.pcsn0 = chip_.input_high(Pin::PCSN0);
  c.pcs1 = chip_.input_high(Pin::PCS1);
  return c;
}

void PinBus::run(const BusCycle& cycle) {
  // A DMA acknowledge sends the access to the FIFO whatever A6-1 and the chip selects say
  // (datasheet Table 1, DMAACKRN / DMAACKTN): it is not a RAM or register cycle.
  const Pin ack = cycle.write ? Pin::DMAACKTN : Pin::DMAACKRN;
  if (!chip_.input_high(ack)) return;
  if (decode_target(cycle) == BusTarget::Both) {
    ++refused_;
    return;
  }
  if (!cycle.write) {
    last_ = chip_.bus(cycle);
    return;
  }
  last_ = chip_.write_strobe_ends(cycle);
  last_.busy = write_busy_;
}

void PinBus::write_starts() {
  // Datasheet 3.5.7 t_MBSY: BUSYN falls from the begin of the write access, so the
  // collision is the strobe start's, though the data is taken at its end.
  const BusCycle cycle = sample(true);
  write_busy_ = chip_.input_high(Pin::DMAACKTN) && decode_target(cycle) == BusTarget::Ram &&
                chip_.write_strobe_starts(cycle);
}

void PinBus::on_strobe_pin() {
  const BusStrobes now = strobes();
  if (active_.read && !now.read) release_data_lines();
  if (active_.write && !now.write) {
    if (!write_cut_) run(sample(true));  // data is taken at the end
    write_cut_ = false;
  }
  const bool read_starts = !active_.read && now.read;
  const bool write_starts_now = !active_.write && now.write;
  active_ = now;
  if (write_starts_now) write_starts();
  if (!read_starts) return;
  last_ = BusResult{};
  run(sample(false));
  driven_ = last_.driven;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (driven_ & (1u << bit)) {
      chip_.set_output(data_pin(bit), sim::level_of(((unsigned{last_.data} >> bit) & 1u) != 0));
    }
  }
}

void PinBus::release_data_lines() {
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (driven_ & (1u << bit)) chip_.set_output(data_pin(bit), sim::Level::HighZ);
  }
  driven_ = 0;
}

void PinBus::on_latch_pin() {
  // Datasheet 3.5.3: while ALEL / ALEH = 1 the latch follows D7-0 / D15-8, at 0 it holds.
  std::uint16_t next = latch_;
  for (unsigned bit = 0; bit < 16; ++bit) {
    const bool open = chip_.input_high(bit < 8 ? Pin::ALEL : Pin::ALEH);
    if (!open) continue;
    const auto m = static_cast<std::uint16_t>(1u << bit);
    next = static_cast<std::uint16_t>(chip_.input_high(data_pin(bit)) ? next | m : next & ~m);
  }
  latch_ = next;
  drive_address_lines();
}

void PinBus::drive_address_lines() {
  // ADMUX = 1: A15-0 are outputs of the latch; ADMUX = 0: inputs, released by the chip.
  const bool out = chip_.input_high(Pin::ADMUX);
  for (unsigned bit = 0; bit < 16; ++bit) {
    const Pin p = address_pin(bit);
    if (out) {
      chip_.set_output(p, sim::level_of(((unsigned{latch_} >> bit) & 1u) != 0));
    } else if (chip_.drives(p)) {
      chip_.set_output(p, sim::Level::HighZ);
    }
  }
}

}  // namespace sercon::chip
