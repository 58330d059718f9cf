// The receiver's side that takes bursts in (line_burst) and lets a burst this chip does not
// look at hop lazily to the next receiver (docs/serial-and-ring.md, "Lazy hops"): the
// conditions, the hop itself, and absorbing the bursts into the timelines when something
// looks. The timeline and the reports are in serial_unit_receiver.cpp.
#include <stdexcept>
#include <string>

#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/chip/serial_unit_receiver_inline.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"

namespace sercon::chip {

using receiver_detail::chain_depth;
using receiver_detail::kMaxChain;

void SerialReceiver::line_burst(const LineBurst& burst) {
  // A chain of lazy hops goes on here from receiver to receiver, one turn per hop (a call
  // per hop cost as much as the hop's checks), counted in chain_depth as the calls were.
  struct Links {
    int before = chain_depth;
    ~Links() { chain_depth = before; }  // the calls out of the loop count up and down as many
  } links;
  check(burst);  // those handed on by pass_through have bits and a bit period (line.hpp)
  SerialReceiver* at = this;
  const LineBurst* b = &burst;
  for (;;) {
    LineListener* next = nullptr;
    SerialReceiver* r = nullptr;  // next->receiver()
    const LineBurst* out = nullptr;
    if (!at->try_lazy_hop(*b, next, r, out)) {
      // Read here. When the repeater hands it on unbooked, the chain goes on in this loop
      // too (a read hop's burst, kept in its forwarded queue), as a call deeper would have.
      const HopTry read = at->read_try_;
      at->read_try_ = HopTry::Full;
      at->absorb_lazy();
      Handed handed;
      if (!(read == HopTry::Full ? at->announce_or_read(*b, handed) : at->read(*b, read, handed)))
        return;
      if (handed.receiver == nullptr || handed.receiver == at) [[unlikely]]
        return hand_copy(*handed.next, *handed.out);
      b = handed.out;
      at = handed.receiver;
      continue;
    }
    ++chain_depth;
    if (r == nullptr || r == at) [[unlikely]]
      return hand_copy(*next, *out);
    b = out;  // the node's lazy burst, read by the next one before anything changes it
    at = r;
  }
}

// `out` is the node's lazy burst: a copy for whatever may change its lazy bursts before it
// has read them (the node itself; a listener that is not a receiver may call out). Out of
// the loop, so the usual hop keeps no copy on its stack.
void SerialReceiver::hand_copy(LineListener& next, const LineBurst& out) {
  const LineBurst copy = out;
  next.line_burst(copy);
}

void SerialReceiver::bad_burst(const LineBurst& burst) {
  if (!burst.bits) throw std::invalid_argument("RxD: a burst without bits");
  throw std::invalid_argument("RxD: a burst with bit period " + std::to_string(burst.bit_period) +
                              " ps");
}

// --- lazy hops ------------------------------------------------------------------------------

void SerialReceiver::set_lazy_hops(bool on) {
  if (!on) absorb_lazy();
  lazy_hops_ = on;
  refresh_hop_period();
  // Off: read hops and the fibre behind TxD take the full path too.
  unit_.repeater().set_forward_unbooked(on);
  unit_.outputs().set_pass_unbooked(on);
}

// With the repeater off nothing hops: a master (REPON = 0) reads every burst it gets without
// asking the rest.
void SerialReceiver::refresh_hop_period() {
  const bool on = lazy_hops_ && unit_.running() && unit_.repeater().on();
  hop_period_ = on ? unit_.bit_period() : 0;
  // forward_time() of a burst that hops (after now, so after time 0): ceil_SCLK(start + 2 bits).
  const SerialRepeater& repeater = unit_.repeater();
  hop_sclk_ = repeater.sclk_period();
  hop_by_sclk_ = repeater.by_sclk();
  hop_due_ = SerialUnit::kRepeaterDelayBits * hop_period_ + hop_sclk_ - 1;
  hop_lag_ = report_lag(hop_period_);
  refresh_report_grid();
  refresh_unrepeated_reads();
}

void SerialReceiver::refresh_report_grid() {
  const sim::Time bit = unit_.bit_period();
  const sim::Time mclk = mclk_.period();
  const sim::Time half_bits = bit > 0 ? receiver_detail::burst_half_bits(bit) : 0;
  const auto exact_limit = static_cast<sim::Time>(mclk_.exact_limit());  // below 2^63
  if (bit <= 0 || exact_limit <= half_bits) {
    grid_ = ReportGrid{};
    return;
  }
  grid_ = ReportGrid{bit,
                     exact_limit - half_bits,
                     half_bits + mclk - 1,
                     mclk,
                     sim::Reciprocal(static_cast<std::uint64_t>(mclk)),
                     bit % mclk == 0};
}

// A burst at its rate after now, of one frame, at such a node: read() takes it as
// announce() would (asking the processor's answers itself, Full). Its decode is only looked
// for (mostly there: the transmitter seeds it), so that this calls nothing but the one it
// hands the burst to (cheaper by its saved registers).
bool SerialReceiver::announce_or_read(const LineBurst& b, Handed& handed) {
  if (unrepeated_reads_ && b.bit_period == unit_.bit_period() && b.start > scheduler_.now() &&
      chain_depth < kMaxChain) {
    const BurstDecode* decode = b.bits.decodes().whole.get();
    if (decode != nullptr && decode->frames.size() == 1) return read(b, HopTry::Full, handed);
  }
  return announce(b, handed);
}

// What consider() would plan for the burst's frames in the telegram processor's present
// state. With one handler only, consider() also marks the other kind of report done for
// good, which a later handler would see: that is left to the full path. Inline: asked at
// every hop. kNote: a burst of one frame wanted is noted in read_try_ for read().
template <bool kNote>
inline bool SerialReceiver::wants_a_report(const LineBurst& b) {
  if (hop_check_ != HopCheck::Frames) return hop_check_ == HopCheck::Always;
  const BurstDecode& decode = decode_burst(b.bits);
  if (!addressed_wanted_ && !decode.to_255) return false;  // may_want() no frame
  for (const wire::DecodedFrame& f : decode.frames) {
    if (!may_want(f)) continue;
    const sim::Time start = b.start + static_cast<sim::Time>(f.start_bit) * b.bit_period;
    if (wants_start(start, f.address)) {
      if (kNote && decode.frames.size() == 1) read_try_ = HopTry::ReadStart;
      return true;
    }
    if (wants_telegram(start, f)) {
      if (kNote && decode.frames.size() == 1) read_try_ = HopTry::ReadTelegram;
      return true;
    }
  }
  return false;
}

inline bool SerialReceiver::try_lazy_hop(const LineBurst& b, LineListener*& next,
                                         SerialReceiver*& receiver, const LineBurst*& out) {
  // Lazy hops on, running (a unit in reset has no bit period), the repeater on and at this
  // chip's rate.
  if (b.bit_period != hop_period_ || chain_depth >= kMaxChain) return false;
  const sim::Time now = scheduler_.now();
  if (b.start <= now) return false;
  // Asked first of the dearer checks: it is the one that fails at a node that reads the
  // burst (the checks have no effects but the note for read(), so their order is free).
  if (wants_a_report<true>(b) || !recactn_.idle()) return false;
  // After everything announced before (nothing superseded or cut) and between good signals
  // (the line monitor hears nothing): announce() would only keep it.
  const auto due = static_cast<std::uint64_t>(b.start + hop_due_);
  const sim::Time leaves = static_cast<sim::Time>(hop_by_sclk_.divide(due)) * hop_sclk_;
  const bool after_lazy = !lazy_.empty();
  if (after_lazy) {
    // After a lazy hop here nothing has changed the repeater or TxD (every way into them
    // absorbs the lazy bursts first), and this burst leaves after that one: their checks
    // hold still, only the listener's own are left.
    const LazyBurst& last = lazy_.back();
    if (last.ends > b.start || last.leaves >= leaves) return false;
    // Those over by now go first, as the full path would prune them (after the push it
    // would find the same: this one has not reached the next receiver yet). Mostly the
    // front of two, the last one having reached it.
    if (lazy_.size() == 2) {
      if (last.reaches() <= now && lazy_.front().reports_over < now) lazy_.drop_front();
    } else {
      prune_lazy(now);
    }
  } else {
    const Entry& last = timeline_.back();
    if (last.segment.since >= b.start || !good(last.segment)) return false;
    if (last.segment.is_burst && b.start < last.cut) return false;
    if (!unit_.repeater().would_pass(leaves)) return false;
  }
  // The burst as it reaches the next receiver, kept (built in its place, every field set,
  // taken back if the listener refuses) and handed on.
  LazyBurst& kept = lazy_.reuse_back();
  kept.reaching.bit_period = b.bit_period;
  kept.reaching.bits.assign_held(b.bits);  // check()ed: it has bits
  kept.arrived = b.start;
  kept.leaves = leaves;
  kept.ends = b.start + static_cast<sim::Time>(b.bits->size()) * b.bit_period;
  kept.reports_over = kept.ends + hop_lag_;  // report_lag(b.bit_period)
  // Set by the listener; set here too, so the entry is whole even if a listener throws.
  kept.reaching.start = leaves;
  TxdOutputs& txd = txd_;
  // Through locals: the slow path's call takes their addresses, which kept the loop's
  // `next` on the stack.
  LineListener* to = nullptr;
  SerialReceiver* r = nullptr;
  PlainLink* const link = hop_link_;  // TxD's lone link, its object not loaded (usual)
  if (link != nullptr ? !link->pass_at(leaves, txd, to, kept.reaching.start, r)
                      : !txd.follower_takes_into(leaves, kept.reaching, to, r)) {
    lazy_.pop_back();
    return false;
  }
  next = to;
  receiver = r;
  if (!after_lazy) txd.set_follower_delay(kept.reaching.start - leaves);  // as line_burst()
  out = &kept.reaching;
  ++lazy_hops_taken_;
  return true;
}

void SerialReceiver::absorb_waiting() {
  const sim::Time now = scheduler_.now();
  if (settle_lazy(now)) return;  // the usual case (serial_unit_pass_through.hpp)
  // Nothing here calls out of the node, so lazy_ stays as it is while it is walked. A
  // booking out of order (a missed trigger) throws; the lazy bursts are let go then, so the
  // node does not throw again at every later absorb.
  struct LetGo {
    sim::SlotQueue<LazyBurst, 32>& lazy;
    ~LetGo() { lazy.drop_all(); }  // as drop_front() lets them go
  } let_go{lazy_};
  for (std::size_t i = 0; i < lazy_.size(); ++i) {
    const LazyBurst& lazy = lazy_[i];
    const LineBurst& b = lazy.reaching;
    expect_absorbed_in_order("RxD", timeline_.back().segment.since, lazy.arrived);
    // In force by now, every entry before it over: it takes the front's place.
    if (lazy.arrived <= now && all_done_with(now)) {
      take_in_front(lazy, lazy.reports_over < now);
    } else {
      prune();
      take(append(RxdSegment{true, LineCondition::Idle, lazy.arrived, b.bit_period, b.bits}));
    }
    unit_.repeater().absorb(lazy.leaves, b.bit_period, b.bits);
  }
}

// Whether the lazy bursts must be absorbed for a plan: one of them has a report the telegram
// processor wants now and whose time may be still to come. Otherwise the full path would plan
// none of theirs now (a report not wanted stays eligible, and is asked again at the next
// plan, as here), so they can stay lazy: a node that fires a report per telegram it reads
// need not book each telegram it passes on. With one handler only, the full path marks
// the other kind done for good: that is left to it.
bool SerialReceiver::lazy_report_due(sim::Time now) {
  if (hop_check_ != HopCheck::Frames) return true;
  for (std::size_t i = 0; i < lazy_.size(); ++i) {
    const LazyBurst& lazy = lazy_[i];
    const LineBurst& b = lazy.reaching;
    if (lazy.reports_over < now) continue;  // its reports are past
    // Asked as at the hop, of the burst as it reached RxD.
    if (wants_a_report<false>(LineBurst{lazy.arrived, b.bit_period, b.bits})) return true;
  }
  return false;
}

}  // namespace sercon::chip
