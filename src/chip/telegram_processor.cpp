#include "sercon/chip/telegram_processor.hpp"

#include "sercon/chip/required_unit.hpp"
#include "sercon/chip/serial_unit_transmitter.hpp"
#include "sercon/chip/telegram_list_walk.hpp"

namespace sercon::chip {
namespace {

using telegram::kCycl;
using telegram::kEn;

constexpr std::uint8_t kMstAddress = kAddress255;
constexpr sim::Time kNone = ReceiveWants::kNone;

bool is_mst(const wire::DecodedFrame& frame) { return ReceiveWants::is_mst(frame); }

}  // namespace

TelegramProcessor::TelegramProcessor(Chip& chip)
    : chip_(chip),
      regs_(chip.regs()),
      scheduler_(chip.scheduler()),
      time_base_(required_unit<TimeBase>(chip, "TelegramProcessor")),
      cycle_control_(required_unit<CycleControl>(chip, "TelegramProcessor")),
      interrupts_(required_unit<Interrupts>(chip, "TelegramProcessor")),
      serial_(required_unit<SerialUnit>(chip, "TelegramProcessor")),
      dma_(required_unit<DmaPort>(chip, "TelegramProcessor")),
      regmode_(field_ref("REGMODE", chip.variant())),
      entmt_(field_ref("ENTMT", chip.variant())),
      phas0_(field_ref("PHAS0", chip.variant())),
      phasr_(field_ref("PHASR", chip.variant())),
      flmdtadr_(field_ref("FLMDTADR", chip.variant())),
      is_816_(chip.variant() == Variant::Sercon816),
      ram_(chip),
      list_(time_base_, ram_, *this),
      transmit_(ram_, dma_),
      receive_(ram_, dma_),
      mst_(time_base_, interrupts_, serial_, ram_) {
  time_base_.on_cycle_start(this, [](void* tp, const CycleStart& start) {
    static_cast<TelegramProcessor*>(tp)->on_cycle_start(start);
  });
  cycle_control_.on_send_mst([this] { on_send_mst(); });
  serial_.on_telegram_start(this, [](void* tp, sim::Time start, std::uint8_t address) {
    static_cast<TelegramProcessor*>(tp)->on_telegram_start(start, address);
  });
  serial_.on_telegram(this, [](void* tp, const ReceivedTelegram& telegram) {
    static_cast<TelegramProcessor*>(tp)->on_telegram(telegram);
  });
  read_fields();
  // Any register: the rare change costs a few loads; most changes are of other registers.
  regs_.on_change_first([this](std::uint8_t) { read_fields(); });
  wants_.header = &list_.wait();
  wants_.other_address_counts = chip.variant() == Variant::Sercon410B;
  serial_.set_interest(this);
  interrupts_.on_clear(Irq::Tend, &TelegramProcessor::tend_cleared, this);
  interrupts_.on_clear(
      Irq::Endmk, [](void* tp) { static_cast<TelegramProcessor*>(tp)->list_.end_may_change(); },
      this);
}

// Only the scheduler is touched: the time base may be gone (it cancels its own events).
TelegramProcessor::~TelegramProcessor() {
  scheduler_.disown(tend_event_);
  scheduler_.cancel(rscend_event_);
}

void TelegramProcessor::reset(ResetCause) {
  list_.stop();
  mst_.stop();
  stop_receiving();
  wants_.flag_clear = kNone;
  scheduler_.cancel_owned(tend_event_);
  tend_held_ = false;
  scheduler_.cancel(rscend_event_);
  rscend_event_ = {};
  serial_.interest_changed();
}

void TelegramProcessor::read_fields() {
  Fields& f = fields_;
  f.master = regmode_.on(regs_);
  f.phase = static_cast<std::uint8_t>((f.master ? phas0_.get(regs_) : phasr_.get(regs_)) & 0x07);
  f.address_flag_phase = !f.master && f.phase <= 2;
  f.entmt = entmt_.on(regs_);
  f.flmdtadr = flmdtadr_.on(regs_);
  f.tend_latched = interrupts_.latched(Irq::Tend);
  f.endmk_latched = interrupts_.latched(Irq::Endmk);
  f.rend_latched = interrupts_.latched(Irq::Rend);
  f.rscend_latched = interrupts_.latched(Irq::Rscend);
}

void TelegramProcessor::set_service_channel_port(ServiceChannelPort* port) {
  port_ = port != nullptr ? port : &pass_through_;
}

// --- cycles -----------------------------------------------------------------------------

void TelegramProcessor::on_cycle_start(const CycleStart& start) {
  const bool is_master = fields().master;
  const bool own_kind =
      is_master ? start.kind == CycleKind::Master : start.kind != CycleKind::Master;
  if (!own_kind) return;
  if (start.kind == CycleKind::Substitute) {
    try {
      ram_.count_error(telegram::kNmsterr);  // a cycle without a valid MST
    } catch (const ListFault& f) {
      list_fault(f);
    }
  }
  // The answers to the receiver change only if a receive header waited before or waits
  // now (ReceiveInterest: the list's answer is NotExpected otherwise, and nothing else
  // they depend on changes here). A slave's list starts with its AT: most cycle starts
  // change nothing.
  const bool waited = list_.waits_for_telegram();
  list_.start(fields().phase <= 2 ? telegram::kCompt0 : telegram::kCompt1);
  if (waited || list_.waits_for_telegram()) serial_.interest_changed();
}

void TelegramProcessor::on_send_mst() {
  if (!master()) return;
  try {
    mst_.send();
  } catch (const ListFault& f) {
    list_fault(f);
  }
}

// --- reception --------------------------------------------------------------------------

// Every telegram is offered to the list when its address is in, address 255 too: an MDT
// to all drives must begin its header as early as any other. One that proves to be an MST
// at its detection is withdrawn again (withdraw_mst).
void TelegramProcessor::on_telegram_start(sim::Time start, std::uint8_t address) {
  offer(start, address);
}

void TelegramProcessor::offer(sim::Time start, std::uint8_t address) {
  if (receiving()) [[unlikely]]
    return offer_while_receiving(start, address);
  offer(start, address, nullptr);
}

// Never detected: lost, as a telegram missed in its window (RERR, NERR, INT_RERR; §10).
// Frames do not overlap and a detection comes before the next frame's start report, so
// this is a guard, not a path the ring takes: its header is kept before the offer takes
// receiving_.item, and receive_missed() runs after stop_receiving() (nothing it reaches
// asks receiving()).
void TelegramProcessor::offer_while_receiving(sim::Time start, std::uint8_t address) {
  const ListItem lost_item = receiving_.item;
  offer(start, address, &lost_item);
}

void TelegramProcessor::offer(sim::Time start, std::uint8_t address, const ListItem* lost_item) {
  // An accepted header goes straight into receiving_ (meaningful only while receiving()).
  ListItem& item = receiving_.item;
  const TelegramList::Match match = list_.offer(start, address, item);
  if (match == TelegramList::Match::OtherAddress) {
    // Delta spec 2.9: the 410B forgets the request only when an MDT with another address
    // comes; the 816 when it starts the answer. An address-255 telegram may be an MST,
    // which is no MDT: it is judged at its detection.
    if (address_flag_phase() && chip_.variant() == Variant::Sercon410B) {
      if (address == kMstAddress) {
        wants_.flag_clear = start;
      } else {
        flmdtadr_.set(regs_, false);
      }
    }
    return;
  }
  if (match != TelegramList::Match::Accepted) return;
  bool flag_set = false;
  if (address_flag_phase() && item.has(telegram::kAchk)) {
    flag_set = !fields().flmdtadr;
    flmdtadr_.set(regs_, true);
  }
  try {
    if (lost_item != nullptr) [[unlikely]] {
      stop_receiving();
      receive_missed(*lost_item);
    }
    receiving_.val_cleared = false;
    receiving_.flag_set = flag_set;
    wants_.receiving = start;
    receiving_.val_cleared = receive_.begin(item);
  } catch (const ListFault& f) {
    stop_receiving();
    list_fault(f);
  }
}

void TelegramProcessor::on_telegram(const ReceivedTelegram& telegram) {
  const bool current = wants_.receiving == telegram.start;  // never kNone
  if (wants_.flag_clear != telegram.start) [[likely]] {
    if (!is_mst(telegram.frame)) {
      if (current) finish_current(telegram);
      return;
    }
    if (!current) return on_mst_telegram(telegram);
  }
  on_telegram_general(telegram);
}

void TelegramProcessor::finish_current(const ReceivedTelegram& telegram) {
  const ListItem& item = receiving_.item;  // kept: stop_receiving() only clears the start
  finish_receive(item, telegram.frame);
  list_.taken(item);  // an address-255 telegram held the walk at its header
}

void TelegramProcessor::on_mst_telegram(const ReceivedTelegram& telegram) {
  const wire::DecodedFrame& frame = telegram.frame;
  // Recognised 5.5 of its own bit times after its end, as its detection was timed.
  if (frame.ok()) on_mst(frame, telegram.end + five_and_a_half_bits(telegram.bit_period));
}

void TelegramProcessor::on_telegram_general(const ReceivedTelegram& telegram) {
  const wire::DecodedFrame& frame = telegram.frame;
  const bool current = wants_.receiving == telegram.start;  // never kNone
  if (wants_.flag_clear == telegram.start) {
    wants_.flag_clear = kNone;
    if (!is_mst(frame)) flmdtadr_.set(regs_, false);  // an MDT to all drives: another address
  }
  if (is_mst(frame)) {
    if (current) withdraw_mst();
    on_mst_telegram(telegram);
    return;
  }
  if (current) finish_current(telegram);
}

void TelegramProcessor::withdraw_mst() {
  const Receiving r = receiving_;
  stop_receiving();
  // Delta spec 2.9: only an MDT with the drive's address requests an AT; an MST taken by a
  // header for address 255 does not.
  if (r.flag_set) flmdtadr_.set(regs_, false);
  try {
    receive_.withdraw(r.item, r.val_cleared);
  } catch (const ListFault& f) {
    list_fault(f);
  }
  list_.reclaim(r.item);
}

// A slave's counter loads at the detection itself: CycleControl's synchroniser is the 3
// MCLK edges the detection already waited (facts §5: t_start from the MST's end to the
// load), so it is handed the recognition point 5.5 bit times after the end, now past.
void TelegramProcessor::on_mst(const wire::DecodedFrame& frame, sim::Time recognised) {
  if (master()) {
    mst_.returned();
    return;
  }
  phasr_.put(regs_, frame.data[0]);
  cycle_control_.mst_detected(recognised);
}

void TelegramProcessor::finish_receive(const ListItem& item, const wire::DecodedFrame& frame) {
  stop_receiving();
  // The usual telegram inline: no outcome to look at (no error, no service work).
  if (receive_.finish_plain(item, frame)) {
    raise_unless_latched(Irq::Rend, fields().rend_latched);
    if (!service_work_pending()) raise_unless_latched(Irq::Rscend, fields().rscend_latched);
    return;
  }
  finish_receive_general(item, frame);
}

void TelegramProcessor::finish_receive_general(const ListItem& item,
                                               const wire::DecodedFrame& frame) {
  ReceivePath::Outcome outcome;
  try {
    outcome = receive_.finish(item, frame, port());
  } catch (const ListFault& f) {
    // Doc §2 "Bad lists": a container or buffer beyond the RAM stops the list for the rest
    // of the cycle, though the walk moved on when the address came (inside a report's
    // handler: no interest_changed()).
    list_.abort(f);
    return;
  }
  interrupts_.raise(Irq::Rend);
  if (outcome.error) interrupts_.raise(Irq::Rerr);
  // Delta spec 2.10.2: INT_RSCEND once the service-container work after a receive telegram
  // is done (at once when there is none, unless earlier work is still going on).
  if (outcome.service_work > 0) {
    after_service_work(outcome.service_work);
  } else if (!service_work_pending()) {
    interrupts_.raise(Irq::Rscend);
  }
}

// Service-container work lasting `work` from now: overlapping work ends with the later of
// the two.
void TelegramProcessor::after_service_work(sim::Time work) {
  const sim::Time at = scheduler_.now() + work;
  if (scheduler_.pending(rscend_event_)) {
    if (at <= rscend_at_) return;
    scheduler_.cancel(rscend_event_);
  }
  rscend_at_ = at;
  rscend_event_ = scheduler_.at(at, &TelegramProcessor::service_work_done, this);
}

void TelegramProcessor::service_work_done(void* processor) {
  auto& self = *static_cast<TelegramProcessor*>(processor);
  self.rscend_event_ = {};
  self.interrupts_.raise(Irq::Rscend);
}

void TelegramProcessor::receive_missed(const ListItem& item) {
  receive_.missed(item);
  interrupts_.raise(Irq::Rerr);
}

// --- transmission -----------------------------------------------------------------------

void TelegramProcessor::transmit_due(const ListItem& item) {
  const Fields& f = fields();
  if (!f.entmt) return;  // delta spec 2.6.2: ENTMT = 0 suppresses ATs and MDTs
  if (!item.has(kCycl) && !item.has(kEn)) return;
  if (f.address_flag_phase && !f.flmdtadr) return;
  const sim::Time now = scheduler_.now();
  // The transmitter itself (SerialUnit's send and transmit_free_at are calls into it).
  if (serial_.bit_period() == 0 || serial_.next_bit_edge(now) < serial_.transmitter().free_at()) {
    ++skipped_;
    return;
  }
  const bool flag_on = is_816_ && fields().flmdtadr;
  std::span<const std::uint8_t> data;
  // The usual telegram in one go: word 0 and its containers read at once (TransmitPath::
  // gather_plain), nothing written, no flag to clear between them.
  if (flag_on || !transmit_.gather_plain(item, data)) {
    const bool val = transmit_.reread_val(item);
    if (item.has(kEn)) transmit_.clear_send_once(item, val);
    // Delta spec 2.9.2: the 816 resets the flag "after starting to send a telegram when
    // initiated when the flag is set": any telegram started while it is set, also an AT of
    // CP3/4 that it did not gate, so a request answered there brings no second AT after a
    // fall back to CP0..2.
    if (is_816_ && fields().flmdtadr) flmdtadr_.set(regs_, false);
    data = transmit_.gather(item, val, port());
  }
  const sim::Time end = serial_.transmitter().send(now, item.adr(), data);
  // Mostly the last telegram's event is held and INT_TEND is latched still: cancelling that
  // event raises nothing, and this one is held in its place.
  if (tend_held_ && fields().tend_latched) [[likely]] {
    scheduler_.hold_owned_anew(tend_event_, end);
    return;
  }
  // The previous telegram's end may be due at this very instant: raise it now. A held one
  // would find the flag latched (its clear queues it).
  if (scheduler_.owned_pending(tend_event_)) {
    scheduler_.cancel_owned(tend_event_);
    if (!tend_held_) interrupts_.raise(Irq::Tend);
  }
  // Mostly INT_TEND is latched (a host clears it now and then): the event is held, not
  // queued, until the flag is cleared (tend_cleared()).
  if (fields().tend_latched) [[likely]] {
    scheduler_.hold_owned(tend_event_, end, &TelegramProcessor::transmission_ended);
    tend_held_ = true;
    return;
  }
  tend_held_ = false;
  scheduler_.arm_owned(tend_event_, end);
}

void TelegramProcessor::transmission_ended(void* processor) {
  static_cast<TelegramProcessor*>(processor)->interrupts_.raise(Irq::Tend);
}

void TelegramProcessor::tend_cleared(void* processor) {
  auto* const self = static_cast<TelegramProcessor*>(processor);
  if (!self->tend_held_) return;
  self->tend_held_ = false;
  self->scheduler_.queue_held(self->tend_event_);
}

void TelegramProcessor::end_reached(const ListItem&) { interrupts_.raise(Irq::Endmk); }

void TelegramProcessor::list_fault(const ListFault&) { ++list_faults_; }

void TelegramProcessor::list_moved() { serial_.interest_changed(); }

// What on_telegram_start would do: offer() acts on a telegram its waiting header takes, and
// on one of another address in its window only where the 410B forgets FLMDTADR (the phase
// can change by register writes the receiver does not hear of, so every 410B offer of
// another address counts).
bool TelegramProcessor::wants_start(sim::Time start, std::uint8_t address) const {
  return wants_.wants_start(start, address);
}

// What on_telegram would do: an MST always counts; any other telegram only when it is the
// one being received, or (410B) the address-255 telegram whose detection clears FLMDTADR.
bool TelegramProcessor::wants_telegram(sim::Time start, const wire::DecodedFrame& frame) const {
  return wants_.wants_telegram(start, frame);
}

// Only a waiting receive header (offer(), wants_start) or a telegram being received
// (wants_telegram) makes a telegram other than an MST count; every change of either comes
// with interest_changed() or inside a report's handler. A pending 410B FLMDTADR clear
// (wants_.flag_clear) is only ever for an address-255 telegram, which is asked for anyway.
bool TelegramProcessor::may_want_addressed() const { return wants_.may_want_addressed(); }

// The address byte is in after the opening flag and the address with at most one stuffed
// bit (17 bits); the receiver reports it 5.5 bits + 3..4 MCLK later (docs/serial-and-ring.md).
sim::Time TelegramProcessor::start_report_delay() const {
  return 23 * serial_.bit_period() + 4 * chip_.mclk_period();
}

}  // namespace sercon::chip
