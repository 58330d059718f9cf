// Who starts SERCOS cycles (docs/timing.md, "Cycle start").
//
// Slave (REGMODE = 0): the telegram processor reports each MST it recognises through
// mst_detected(); 3 to 4 MCLK periods after the recognition (synchroniser) the counter is
// loaded with TCNTST and INT_CYCST is raised. The JTSCYC window judges each MST; when a window
// closes empty the chip free-wheels a substitute cycle.
// Master (REGMODE = 1): cycles start from the internal timer every TSCYC µs (PRESYNC = 0)
// or at each active CYC_CLK edge (PRESYNC = 1, edge by CYCPOL, judged by the window).
// At a cycle start the counter is loaded with TCNTST; TCYCSTART µs later the MST is due:
// INT_CYCST is raised and the on_send_mst listeners (telegram processor, watchdog) run.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/cycle_window.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/tick_alarm.hpp"
#include "sercon/chip/time_base.hpp"
#include "sercon/sim/signal.hpp"

namespace sercon::chip {

class Chip;

class CycleControl : public ChipUnit {
 public:
  enum class Mode : std::uint8_t { Slave, MasterTimer, MasterCycClk };

  explicit CycleControl(Chip& chip);
  CycleControl(TimeBase& time_base, Interrupts& interrupts, sim::Signal& cyc_clk);
  ~CycleControl() override;

  void reset(ResetCause cause) override;
  void release() override;

  // Slave entry point for the telegram processor: the serial receiver has recognised an
  // MST at `when`, 5.5 bit times after the end of the MST. The counter loads at the third
  // MCLK edge after the first at or after it, the delay the driver's TCNTST compensates
  // (facts §5 t_start). `when` may be past (the telegram processor hears of the MST at that
  // load edge); a load before now is std::invalid_argument. Ignored in master mode when the
  // load would happen, and while the chip is in reset.
  void mst_detected(sim::Time when);
  // Master: "send the MST now", TCYCSTART µs after each cycle start.
  void on_send_mst(std::function<void()> listener);

  Mode mode() const { return mode_; }
  const CycleWindow& window() const { return window_; }

 private:
  Mode mode_from_registers() const;
  void switch_mode(Mode mode);
  void on_register_change(std::uint8_t address);
  void on_cyc_clk(sim::Level level);
  // `action(this)` at `at` (function + context: no std::function per MST).
  void recognise_at(sim::Time at, sim::Scheduler::Action action, bool cyc_clk);
  // mst_detected() of an MST loading the counter later than now (mst_load_edge_ set), or
  // while one is pending.
  [[gnu::noinline]] void mst_later(sim::Time load);
  static void cyc_clk_action(void* control);
  static void slave_mst_action(void* control);  // a recognition's (recognitions_)
  static void owned_mst_action(void* control);  // mst_event_'s, at mst_load_edge_
  [[noreturn, gnu::cold, gnu::noinline]] void refuse_past_load(sim::Time when,
                                                               sim::Time load) const;
  void start_timer_now();
  void master_cycle_start();
  void cyc_clk_recognised();
  void slave_mst(Edge load);
  void mst_due();
  bool master_cycle_starts_now() const;
  void send_mst();
  // Ahead of the time base's cycle-start listeners (TimeBase::start_cycle's `first`):
  // `start` is still the counter and TSCYC now. Inline: a step of every cycle start.
  void on_cycle_start(const CycleStart& start) {
    const bool slave_cycle = mode_ == Mode::Slave && start.kind != CycleKind::Master;
    const bool synced_master = mode_ == Mode::MasterCycClk && start.kind == CycleKind::Master;
    if (slave_cycle || synced_master) window_.expect_next(start);
  }
  void on_divider_change(Edge edge, std::int64_t period);
  // INT_CYCST, raised at every cycle start: mostly latched already, when the raise changes nothing.
  void raise_cycst() {
    if (!cycst_latched_) interrupts_.raise(Irq::Cycst);
  }
  void cancel_own_events();
  void cancel_all();

  TimeBase& time_base_;
  RegisterFile& regs_;
  sim::Scheduler& scheduler_;
  Interrupts& interrupts_;
  sim::Signal& cyc_clk_;
  FieldRef regmode_, presync_, cycpol_;
  CycleWindow window_;
  bool running_ = false;
  Mode mode_ = Mode::Slave;
  bool cyc_clk_high_ = true;
  // INT_CYCST latched, kept as data: read again at every register value change by a listener
  // that runs before all others (RegisterFile::on_change_first).
  bool cycst_latched_ = false;
  bool timer_idle_ = false;   // master timer waiting for a non-zero TSCYC
  DividerTicks cycle_ticks_;  // master: restarted at each cycle start
  TickAlarm next_cycle_;
  TickAlarm mst_send_;
  struct Recognition {
    sim::Scheduler::EventId event;
    bool cyc_clk;  // a CYC_CLK edge (a master's cycle start), not a slave's MST
  };
  std::vector<Recognition> recognitions_;  // MSTs / CYC_CLK edges in the synchroniser
  // A slave's MST in the synchroniser: one owned slot (an event a cycle, no EventId to keep);
  // an MST while it is pending takes recognitions_.
  sim::Scheduler::OwnedSlot mst_event_;
  Edge mst_load_edge_ = 0;  // mst_event_'s time as an MCLK edge, while it is pending
  std::vector<std::function<void()>> send_mst_listeners_;
};

}  // namespace sercon::chip
