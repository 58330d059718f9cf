// The telegram processor (datasheet §1 "Telegram processing", 4.2; delta spec 2.6.2, 2.9,
// 2.10; docs/telegram-processing.md): walks the DPRAM telegram list of the phase in every
// cycle, sends the list's telegrams and the master's MST through the serial unit, stores
// received telegrams, and keeps the status words, counters and interrupts of all that.
//
// Cycles come from the time base: a slave's list starts at every cycle start the MST (or
// the free-wheel) makes, a master's at every cycle start of its timer / CYC_CLK; times in
// the list are cycle-counter values (µs after the end of the MST at this node, for a
// master: of its cycle, see the document). Work happens per telegram, never per bit.
#pragma once

#include <cstdint>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/cycle_control.hpp"
#include "sercon/chip/dma_port.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/service_channel_port.hpp"
#include "sercon/chip/telegram_list.hpp"
#include "sercon/chip/telegram_master.hpp"
#include "sercon/chip/telegram_ram.hpp"
#include "sercon/chip/telegram_receive.hpp"
#include "sercon/chip/telegram_transmit.hpp"
#include "sercon/chip/time_base.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class Chip;

// Final: its list calls its ListClient handlers directly (BasicTelegramList).
class TelegramProcessor final : public ChipUnit, private ListClient, private ReceiveInterest {
 public:
  explicit TelegramProcessor(Chip& chip);
  ~TelegramProcessor() override;

  void reset(ResetCause cause) override;

  // The service-container engine (next to come); nullptr restores the pass-through.
  void set_service_channel_port(ServiceChannelPort* port);

  // Diagnostics the registers do not show (docs/telegram-processing.md, "Bad lists"):
  // list walks stopped by a fault, and list telegrams not sent because the own
  // transmitter was still busy (or its clocks off) at their time.
  std::uint64_t list_faults() const { return list_faults_; }
  std::uint64_t transmissions_skipped() const { return skipped_; }

 private:
  friend class BasicTelegramList<TelegramProcessor>;  // calls the ListClient handlers

  // The telegram being received; its start is wants_.receiving (kNone: none).
  struct Receiving {
    ListItem item;
    bool val_cleared = false;  // begin() cleared VAL (undone if it proves to be an MST)
    // The offer set FLMDTADR, which was 0 before: put back if it proves to be an MST (the
    // header waits as if it had not been offered).
    bool flag_set = false;
  };

  // The register fields the handlers test at every cycle start, telegram start and list
  // transmission, as data: read again at every change of a register value (RegisterFile::
  // on_change_first: before any other listener, so whatever runs after the change sees
  // them current; in a steady ring no value changes). Each use asks fields() again, so a
  // change between two uses (a write of FLMDTADR, a flag raised) is seen as a read would.
  struct Fields {
    bool master = false;  // REGMODE
    // PHAS0 (the byte a master sends) in master mode, PHASR (the byte of the last MST
    // received) in slave mode, bits 0..2.
    std::uint8_t phase = 0;
    // Delta spec 2.9: in phases 1 and 2 a drive answers only when the master asked it. The
    // chip tells phases apart only as 0..2 and 3..7 (COMPT0/1, TSCYC0/1), and a drive must
    // not send at all in CP0 (facts §2), so the gate holds in phase 0 too
    // (docs/telegram-processing.md). A slave in CP0..2: FLMDTADR gates the ATs.
    bool address_flag_phase = false;
    bool entmt = false;
    bool flmdtadr = false;
    bool tend_latched = false;    // INT_TEND
    bool endmk_latched = false;   // INT_ENDMK
    bool rend_latched = false;    // INT_REND
    bool rscend_latched = false;  // INT_RSCEND
  };
  const Fields& fields() const { return fields_; }
  void read_fields();
  bool master() const { return fields().master; }
  bool address_flag_phase() const { return fields().address_flag_phase; }
  ServiceChannelPort& port() { return *port_; }
  // A telegram is being received: receiving_ holds it (wants_.receiving is its start).
  bool receiving() const { return wants_.receiving != ReceiveWants::kNone; }
  void stop_receiving() { wants_.receiving = ReceiveWants::kNone; }

  [[gnu::flatten]] void on_cycle_start(const CycleStart& start);
  void on_send_mst();
  [[gnu::flatten]] void on_telegram_start(sim::Time start, std::uint8_t address);
  // The two usual telegrams told apart inline (in the serial unit's handler), before any
  // register is saved: the one being received (finish_current) and an MST for no header
  // (on_mst_telegram, a slave's cycle start); the rest out of line (on_telegram_general).
  inline void on_telegram(const ReceivedTelegram& telegram);
  // Flattened: the walk on past a header held for an address-255 telegram (list_.taken)
  // inlines into it, no call of its own.
  [[gnu::flatten, gnu::noinline]] void finish_current(const ReceivedTelegram& telegram);
  [[gnu::noinline]] void on_mst_telegram(const ReceivedTelegram& telegram);
  // Any telegram, the rare ones too (a 410B FLMDTADR clear pending, an MST taken by a header).
  [[gnu::noinline]] void on_telegram_general(const ReceivedTelegram& telegram);
  void on_mst(const wire::DecodedFrame& frame, sim::Time recognised);
  // offer() and finish_receive() are inline (defined in the .cpp, each called once there): a
  // telegram's start and its detection are one call each from the serial unit
  // (finish_receive() a call of its own cost about 14 a telegram).
  inline void offer(sim::Time start, std::uint8_t address);
  // A start report while a telegram is still being received (a guard): the offer with that
  // telegram's header, missed if the new one is accepted. Out of line: the usual offer keeps
  // no copy of it.
  [[gnu::noinline]] void offer_while_receiving(sim::Time start, std::uint8_t address);
  // `lost_item`: the header of a telegram never detected (nullptr: none).
  inline void offer(sim::Time start, std::uint8_t address, const ListItem* lost_item);
  // Out of line: finish_current is flattened, and an MST taken by a header is rare.
  [[gnu::noinline]] void withdraw_mst();
  // `item`: the header receiving_ holds (stop_receiving() leaves it as it is).
  [[gnu::always_inline]] inline void finish_receive(const ListItem& item,
                                                    const wire::DecodedFrame& frame);
  // Any other telegram (ReceivePath::finish). Out of line: finish_current is flattened, and
  // this path's interrupts and list faults would crowd the usual one.
  [[gnu::noinline]] void finish_receive_general(const ListItem& item,
                                                const wire::DecodedFrame& frame);
  void after_service_work(sim::Time work);
  // interrupts_.raise(irq) unless `latched` (a field of fields()) says it would change
  // nothing. The raise refreshes the fields, also if a listener clears the flag again.
  void raise_unless_latched(Irq irq, bool latched) {
    if (!latched) interrupts_.raise(irq);
  }
  // INT_RSCEND waits for service-container work: mostly none was ever started (no id: a
  // scheduled event's generation is odd, never 0).
  bool service_work_pending() const {
    return rscend_event_.generation != 0 && scheduler_.pending(rscend_event_);
  }
  // Scheduler actions (function + context: no std::function per telegram).
  static void transmission_ended(void* processor);
  static void tend_cleared(void* processor);  // INT_TEND cleared: a held event is queued
  static void service_work_done(void* processor);

  // ListClient
  void transmit_due(const ListItem& item) override;
  void receive_missed(const ListItem& item) override;
  void end_reached(const ListItem& item) override;
  bool end_changes_nothing() const override { return fields().endmk_latched; }
  void list_fault(const ListFault& fault) override;
  sim::Time start_report_delay() const override;
  void list_moved() override;

  // ReceiveInterest: the receiver reports only what this would act on.
  bool wants_start(sim::Time start, std::uint8_t address) const override;
  bool wants_telegram(sim::Time start, const wire::DecodedFrame& frame) const override;
  bool may_want_addressed() const override;
  const ReceiveWants* published() const override { return &wants_; }

  Chip& chip_;
  RegisterFile& regs_;
  sim::Scheduler& scheduler_;
  TimeBase& time_base_;
  CycleControl& cycle_control_;
  Interrupts& interrupts_;
  SerialUnit& serial_;
  DmaPort& dma_;
  FieldRef regmode_, entmt_, phas0_, phasr_, flmdtadr_;
  const bool is_816_;  // the variant is the SERCON816
  Fields fields_;      // read_fields() at construction and at every register change
  TelegramRam ram_;
  BasicTelegramList<TelegramProcessor> list_;
  TransmitPath transmit_;
  ReceivePath receive_;
  MasterMst mst_;
  PassThroughServiceChannel pass_through_;
  ServiceChannelPort* port_ = &pass_through_;
  Receiving receiving_;  // meaningful while receiving()
  // What the receiver compares frames with: the list's wait, the start of the telegram
  // being received (receiving_), and (flag_clear) 410B: the start of an address-255 telegram
  // that came while an ACHK = 1 header for another address waited; FLMDTADR is cleared at
  // its detection unless it is an MST.
  ReceiveWants wants_;
  // INT_TEND at the end of each telegram sent: one owned slot for the processor's life.
  sim::Scheduler::OwnedSlot tend_event_ =
      scheduler_.own(&TelegramProcessor::transmission_ended, this);
  // INT_REND / INT_RSCEND known to be latched: raised since the flag was last cleared
  // (Interrupts::on_clear), so a raise changes nothing. Mostly a host clears them now and
  // then, and every received telegram raises both.
  // tend_event_ is held (Scheduler::hold_owned): INT_TEND was latched when it was armed and
  // has not been cleared since.
  bool tend_held_ = false;
  sim::Scheduler::EventId rscend_event_{};
  sim::Time rscend_at_ = 0;
  std::uint64_t list_faults_ = 0;
  std::uint64_t skipped_ = 0;
};

}  // namespace sercon::chip
