// The serial interface (datasheet §1, delta spec 2.3): transmitter on TxD1-6, receiver on
// RxD, repeater (REPON), line monitor (RDIST, FIBBR, RECACT, L_ERRN). It works per
// telegram, never per bit: telegrams are LineBursts (line.hpp) with exact picosecond
// start times, decoded once per shared bits object. docs/serial-and-ring.md has every
// behaviour and decision.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/sim/reciprocal.hpp"
#include "sercon/sim/time.hpp"
#include "sercon/wire/decoder.hpp"

namespace sercon::chip {

class Chip;
class SerialTransmitter;
class SerialReceiver;
class SerialRepeater;
class LineMonitor;
class TxdOutputs;

// A telegram is recognised 5.5 bit times after its end (or after its address byte, for the
// start report); the MCLK synchroniser then adds 3 edges (facts §5 t_start = 5.5·t_bit +
// 3.5/f_MCLK; docs/serial-and-ring.md, "Receiver"). Rounded up to whole picoseconds.
constexpr sim::Time five_and_a_half_bits(sim::Time bit_period) { return (11 * bit_period + 1) / 2; }
// The synchroniser's edges: a report (and a slave's MST counter load, CycleControl) comes at
// the kDetectionEdges-th MCLK edge after the first at or after that point. One constant for
// both: a slave loads its counter at the very edge its receiver reports the MST.
constexpr int kDetectionEdges = 3;

// A telegram the receiver has decoded (or cut off by an error).
struct ReceivedTelegram {
  sim::Time start;     // first bit of the opening flag at RxD
  sim::Time end;       // end of the closing flag's last bit at RxD (or where the error cut it)
  sim::Time detected;  // first MCLK edge at or after end + 5.5 bit + 3 MCLK (facts §5)
  // The bit time it came at, which `detected` counts in (a rate change after its end
  // leaves it the telegram's own: "Another bit rate").
  sim::Time bit_period;
  // Address, data, error class. Valid only during the on_telegram callback: it may be the
  // memoized decode shared with every other chip that received the same bits.
  const wire::DecodedFrame& frame;
};

// A receive header's wait, as the telegram list keeps it (the list's own state, read by the
// receiver as data): while `waits`, a telegram whose opening flag begins in the window
// [opens, closes) (any time without `tchk`) is the header's if `achk` is off or it brings
// `address`.
struct HeaderWait {
  bool waits = false;
  bool tchk = false;
  bool achk = false;
  std::uint8_t address = 0;
  sim::Time opens = 0, closes = 0;  // with tchk
  bool in_window(sim::Time start) const { return !tchk || (start >= opens && start < closes); }
};

// What the telegram processor acts on, published as data that it keeps current at every
// change (ReceiveInterest::published): the receiver compares a frame with it without a call.
struct ReceiveWants {
  static constexpr sim::Time kNone = std::numeric_limits<sim::Time>::min();
  // An MST is address 255 with one data byte (sercos-facts §2); one with a bad FCS is still
  // an MST (a broken one), never a list telegram.
  static bool is_mst(const wire::DecodedFrame& frame) {
    if (frame.address != kAddress255) return false;  // most frames: decided by the address
    const bool whole =
        frame.error == wire::FrameError::None || frame.error == wire::FrameError::BadFcs;
    return whole && frame.data.size() == 1;
  }

  const HeaderWait* header = nullptr;  // the list's
  bool other_address_counts = false;   // a telegram of another address in the window counts
  sim::Time receiving = kNone;         // start of the telegram being received
  sim::Time flag_clear = kNone;        // start of a telegram whose detection clears a flag

  // Start report: the waiting header's telegram (or, if they count, another address in its
  // window).
  bool wants_start(sim::Time start, std::uint8_t address) const {
    if (!header->waits || !header->in_window(start)) return false;
    return !header->achk || address == header->address || other_address_counts;
  }
  // Detection: every MST, the telegram being received, the one that clears a flag.
  bool wants_telegram(sim::Time start, const wire::DecodedFrame& frame) const {
    return start == receiving || start == flag_clear || is_mst(frame);
  }
  // False: both answers are false for every telegram whose address is not 255.
  bool may_want_addressed() const { return header->waits || receiving != kNone; }
};

// What the telegram processor would act on in its present state. The receiver spends an
// event only on reports it wants; the processor calls SerialUnit::interest_changed()
// whenever its answers may change (its list walk moved on, a telegram was accepted, reset).
// An answer must only read the processor's own state: the receiver asks while it walks its
// timeline, and a call back into the serial unit (a RECACT read, say) could change it.
class ReceiveInterest {
 public:
  virtual ~ReceiveInterest() = default;
  // The address of a telegram whose opening flag began at `start` is in.
  virtual bool wants_start(sim::Time start, std::uint8_t address) const = 0;
  // A telegram that began at `start` is detected (whole or cut off by an error).
  virtual bool wants_telegram(sim::Time start, const wire::DecodedFrame& frame) const = 0;
  // False: both answers are false for every telegram whose address is not 255, whatever its
  // start, until the processor calls interest_changed() or is handed a report. Lets the
  // receiver pass such telegrams on without asking (a lazy hop asks at every node).
  virtual bool may_want_addressed() const { return true; }
  // The same answers as data, kept current by the processor at every change (the receiver
  // then makes no call); nullptr: ask the functions above.
  virtual const ReceiveWants* published() const { return nullptr; }
};

class SerialUnit : public ChipUnit {
 public:
  using TelegramStartHandler = std::function<void(sim::Time start, std::uint8_t address)>;
  using TelegramHandler = std::function<void(const ReceivedTelegram&)>;
  // The same handlers as a plain function and its context, called without std::function's
  // indirection (the telegram processor's, at every report).
  using TelegramStartFn = void (*)(void* context, sim::Time start, std::uint8_t address);
  using TelegramFn = void (*)(void* context, const ReceivedTelegram& telegram);

  static constexpr unsigned kTxdCount = 6;
  // The repeater passes RxD on to TxD this many bit times after it arrives, rounded up to
  // the SCLK grid (docs/serial-and-ring.md, "Repeater").
  static constexpr unsigned kRepeaterDelayBits = 2;

  explicit SerialUnit(Chip& chip);
  ~SerialUnit() override;

  void reset(ResetCause cause) override;
  void release() override;

  // One bit time at the present rate (Chip::serial_clocks()); 0 while the clocks are off.
  sim::Time bit_period() const { return bit_period_; }

  // First TxC edge at or after t: the transmit bit clock ticks at k * bit_period() from
  // time 0 (SCLK grid), and a telegram can only begin on a tick. Inline: asked twice for
  // every telegram sent; the division by the cached reciprocal (a 64-bit division is slow).
  sim::Time next_bit_edge(sim::Time t) const {
    if (bit_period_ == 0 || t <= 0) return t;
    const auto ticks = bit_grid_.divide(static_cast<std::uint64_t>(t + bit_period_ - 1));
    return static_cast<sim::Time>(ticks) * bit_period_;
  }

  // --- transmitter (the telegram processor's side) ---------------------------------------
  // Sends address + data as one telegram whose opening flag starts at the first TxC edge at
  // or after `start` (>= now): next_bit_edge(start), which is `start` itself when it is on
  // the bit grid. Returns the end time (end of the closing flag), so the actual start is
  // end - burst_duration(). Throws std::logic_error if it overlaps the unit's own previous
  // transmission, the clocks are off or the chip is in reset; std::invalid_argument if
  // `start` is in the past. Whether the telegram is allowed (ENTMT etc.) is the caller's
  // business; output enables, test modes and polarity are this unit's.
  sim::Time send(sim::Time start, std::uint8_t address, std::span<const std::uint8_t> data);
  // How long send() would keep the line busy (flags, stuffing included) at the present rate.
  sim::Time burst_duration(std::uint8_t address, std::span<const std::uint8_t> data) const;
  // End of the last own telegram (0 before the first): the earliest start for the next.
  sim::Time transmit_free_at() const;

  // --- receiver events, called at the simulated time they happen -------------------------
  // Once the address byte is in: opening flag + address (with stuffing) + pipeline delay.
  void on_telegram_start(TelegramStartHandler handler);
  void on_telegram_start(void* context, TelegramStartFn handler);
  // At ReceivedTelegram::detected, for every frame the decoder reports (errors included),
  // as far as the interest (below) wants it.
  void on_telegram(TelegramHandler handler);
  void on_telegram(void* context, TelegramFn handler);
  // Only reports `interest` wants are made (nullptr: all). It must outlive the unit or be
  // taken back with nullptr.
  void set_interest(const ReceiveInterest* interest);
  void interest_changed();

  // --- ring side -------------------------------------------------------------------------
  // When the repeater passes on a change that reaches RxD at `arrival`: kRepeaterDelayBits
  // bit times later, rounded up to the SCLK grid.
  sim::Time repeated_at(sim::Time arrival) const;
  LineListener& rxd();  // fibres / buses deliver here
  // Lazy hops (docs/serial-and-ring.md): on by default; off, every telegram takes the full
  // path through this node. A speed option: the results are the same either way.
  void set_lazy_hops(bool on);
  std::uint64_t lazy_hops_taken() const;  // bursts passed on lazily so far
  // TxDn (n = 1..6) -> a fibre / bus input. The listener is told the present condition at
  // once. Replaces an earlier listener on that pin; the listener replaced (or disconnected)
  // is told Dark at once, unless another pin still drives it. std::out_of_range for other n.
  void connect_txd(unsigned pin, LineListener& listener);
  void disconnect_txd(unsigned pin);

  // Bursts decoded, one per bits object, counting those the transmitter seeded when it made
  // them; a burst whose bits were already decoded (by this or any other chip) is served from
  // the shared memo. For tests and benchmarks.
  static std::size_t decode_count();

  // The parts, for each other (src/chip/serial_unit_*.cpp).
  Chip& chip() { return chip_; }
  const Chip& chip() const { return chip_; }
  const SerialFields& fields() const { return fields_; }
  bool running() const { return running_; }  // released from reset
  SerialTransmitter& transmitter() { return *transmitter_; }
  SerialReceiver& receiver() { return *receiver_; }
  SerialRepeater& repeater() { return *repeater_; }
  LineMonitor& monitor() { return *monitor_; }
  TxdOutputs& outputs() { return *outputs_; }

 private:
  sim::Time compute_bit_period() const;
  void on_register_change(std::uint8_t address);
  std::uint16_t control_bits() const;  // 0x02 without its status bits

  Chip& chip_;
  SerialFields fields_;
  bool running_ = false;
  sim::Time bit_period_ = 0;     // cached: Chip::serial_clocks() looks fields up by name
  sim::Reciprocal bit_grid_{0};  // bit_period_'s, for next_bit_edge()
  void set_bit_period(sim::Time period) {
    bit_period_ = period;
    bit_grid_ = sim::Reciprocal(static_cast<std::uint64_t>(period));
  }
  bool repon_ = false, poltxd_ = false;
  std::uint16_t control_ = 0;
  std::unique_ptr<TxdOutputs> outputs_;
  std::unique_ptr<SerialTransmitter> transmitter_;
  std::unique_ptr<SerialReceiver> receiver_;
  std::unique_ptr<SerialRepeater> repeater_;
  std::unique_ptr<LineMonitor> monitor_;
};

}  // namespace sercon::chip
