// sercon.h, "Callbacks": "a pin callback may read and write registers, RAM and pins". A
// driver's interrupt handler run from the INT0 callback must leave the chip as the same
// register writes made right after the callback's sercon_sim_run_until() returns.
#include <gtest/gtest.h>

#include <cstdint>

#include "sercon/sercon.h"

namespace {

constexpr uint32_t kPhase = 0x0A;
constexpr uint32_t kMclkDiv = 0x0E;
constexpr uint32_t kWdCtrl = 0x28;
constexpr uint32_t kTwdog = 0x2A;
constexpr uint16_t kWdogStart = 0x0001;
constexpr uint16_t kIntWdog = 0x0002;  // W1C: CLR_INT_WDOG
constexpr uint16_t kEn0IntWdog = 0x0008;

struct Isr {
  sercon_chip* chip = nullptr;
  int calls = 0;
};

// The interrupt handler: on INT0 going active, acknowledge INT_WDOG.
void watchdog_isr(void* user, sercon_pin, sercon_level level, int64_t) {
  auto* isr = static_cast<Isr*>(user);
  if (level != SERCON_HIGH) return;
  ++isr->calls;
  const int32_t wdctrl = sercon_reg_read(isr->chip, kWdCtrl);
  if (wdctrl >= 0 && (wdctrl & kIntWdog) != 0) sercon_reg_write(isr->chip, kWdCtrl, kIntWdog);
}

// Returns PHASE after the watchdog expired, INT_WDOG was acknowledged (from the INT0
// callback or after run_until) and PHASE was written 3.
int32_t phase_after_acknowledged_expiry(bool acknowledge_in_callback, int* isr_calls,
                                        int32_t* wdctrl_after) {
  sercon_sim* sim = sercon_sim_new();
  sercon_chip_config config;
  sercon_chip_config_default(&config);
  sercon_chip* chip = sercon_chip_new(sim, &config);
  Isr isr{chip, 0};
  if (acknowledge_in_callback) {
    EXPECT_EQ(sercon_on_pin_change(chip, SERCON_PIN_INT0, watchdog_isr, &isr), SERCON_OK);
  }
  EXPECT_EQ(sercon_reg_write(chip, kMclkDiv, 31), SERCON_OK);  // 1 us ticks at 32 MHz
  EXPECT_EQ(sercon_reg_write(chip, kTwdog, 10), SERCON_OK);    // expires after 10 us
  EXPECT_EQ(sercon_reg_write(chip, kWdCtrl, kEn0IntWdog | kWdogStart), SERCON_OK);
  EXPECT_EQ(sercon_sim_run_until(sim, 100'000'000), SERCON_OK);  // 100 us
  if (!acknowledge_in_callback) {
    EXPECT_NE(sercon_reg_read(chip, kWdCtrl) & kIntWdog, 0);  // it did expire
    EXPECT_EQ(sercon_reg_write(chip, kWdCtrl, kIntWdog), SERCON_OK);
  }
  *isr_calls = isr.calls;
  *wdctrl_after = sercon_reg_read(chip, kWdCtrl);
  EXPECT_EQ(sercon_reg_write(chip, kPhase, 3), SERCON_OK);
  const int32_t phase = sercon_reg_read(chip, kPhase);
  sercon_sim_free(sim);
  return phase;
}

// Delta spec 2.6.2: PHAS0 is not writable until INT_WDOG is cleared. Cleared after
// run_until, PHASE takes the write; cleared by the INT0 callback it must too (the lock has
// to be in place before the raise runs the handler, or it outlives the clear).
TEST(CApiCallbackReentry, AcknowledgingTheWatchdogFromTheInt0CallbackUnlocksPhase) {
  int calls = 0;
  int32_t wdctrl = 0;
  ASSERT_EQ(phase_after_acknowledged_expiry(false, &calls, &wdctrl), 3);
  EXPECT_EQ(wdctrl & kIntWdog, 0);

  const int32_t phase = phase_after_acknowledged_expiry(true, &calls, &wdctrl);
  ASSERT_EQ(calls, 1);              // the handler ran once
  EXPECT_EQ(wdctrl & kIntWdog, 0);  // and cleared INT_WDOG
  EXPECT_EQ(phase, 3) << "PHASE is still locked although INT_WDOG was cleared";
}

}  // namespace
