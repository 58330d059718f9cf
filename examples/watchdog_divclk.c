/* Programs the SERCON816's DIV_CLK output and watchdog through the C API, the way a
 * host driver would through the bus, and checks what the pins do:
 *   - a master chip with 1 us time base (MCLKDIV) and 1000 us cycles (TSCYC0);
 *   - DIV_CLK in the 410B mode: NDIVCLK = 3 pulses per cycle at 100, 350, 600 us
 *     (TDIVCLK, DTDIVCLK), then the 816's mode 1: one pulse every NDIVCLK = 2 cycles
 *     (delta spec 2.7);
 *   - the watchdog with TWDOG = 500 us, triggered by software (0x42 to WDOG_TRIG) every
 *     200 us, then left alone: it expires 500 us after the last trigger, sets INT_WDOG,
 *     raises INT0 (EN0_INT_WDOG) and pulls WDOGN low for 2 to 3 us (delta spec 2.6).
 * Prints what it saw and "watchdog_divclk: OK" when every check holds (exit code 0). */
#include <stdint.h>
#include <stdio.h>

#include "sercon/sercon.h"

#define US 1000000LL /* picoseconds per microsecond */

/* Register word addresses (docs/registers.md). */
enum {
  SERMODE = 0x01,
  MCLKDIV = 0x0E,
  TSCYC0 = 0x0F,
  TDIVCLK = 0x1E,
  DTDIVCLK = 0x1F,
  DIVCTRL = 0x20,
  WDCTRL = 0x28,
  WDTRIG = 0x29,
  TWDOG = 0x2A
};

enum {
  REGMODE = 0x0020,    /* SERMODE: master */
  DIVCLKMODE = 0x0200, /* DIVCTRL: one pulse every NDIVCLK cycles */
  WDOG_START = 0x0001, /* WDCTRL, write; reads WDOG_STAT */
  INT_WDOG = 0x0002,   /* WDCTRL, write 1 to clear (CLR_INT_WDOG) */
  WDOUT_SET = 0x0004,  /* WDCTRL, write; reads WDOUT_STAT */
  EN0_INT_WDOG = 0x0008
};

struct seen {
  int divclk_rises;
  int64_t divclk_first_rise;
  int64_t wdogn_fall;
  int64_t wdogn_rise;
  int64_t int0_rise;
};

static void on_pin(void* user, sercon_pin pin, sercon_level level, int64_t t_ps) {
  struct seen* s = (struct seen*)user;
  if (pin == SERCON_PIN_DIV_CLK && level == SERCON_HIGH) {
    if (s->divclk_rises == 0) s->divclk_first_rise = t_ps;
    ++s->divclk_rises;
  } else if (pin == SERCON_PIN_WDOGN) {
    if (level == SERCON_LOW) s->wdogn_fall = t_ps;
    if (level == SERCON_HIGH) s->wdogn_rise = t_ps;
  } else if (pin == SERCON_PIN_INT0 && level == SERCON_HIGH) {
    s->int0_rise = t_ps;
  }
}

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "watchdog_divclk: FAILED: %s (%s)\n", what, sercon_last_error());
    ++failures;
  }
}

static void write_reg(sercon_chip* chip, uint32_t address, uint16_t value) {
  check(sercon_reg_write(chip, address, value) == SERCON_OK, "register write");
}

static void run_for(sercon_sim* sim, int64_t ps) {
  check(sercon_sim_run_until(sim, sercon_sim_now_ps(sim) + ps) == SERCON_OK, "run");
}

int main(void) {
  struct seen s = {0, -1, -1, -1, -1};
  sercon_chip_config config;
  sercon_sim* sim = sercon_sim_new();
  sercon_chip* chip;
  int64_t last_trigger;
  int32_t status;
  int i;

  sercon_chip_config_default(&config); /* SERCON816, MCLK 32 MHz, SCLK 64 MHz */
  chip = sercon_chip_new(sim, &config);
  if (chip == NULL) {
    fprintf(stderr, "watchdog_divclk: %s\n", sercon_last_error());
    return 1;
  }
  check(sercon_on_pin_change(chip, SERCON_PIN_DIV_CLK, on_pin, &s) == SERCON_OK, "watch");
  check(sercon_on_pin_change(chip, SERCON_PIN_WDOGN, on_pin, &s) == SERCON_OK, "watch");
  check(sercon_on_pin_change(chip, SERCON_PIN_INT0, on_pin, &s) == SERCON_OK, "watch");

  /* Time base and cycle: 32 MHz / (31 + 1) = 1 us; 1000 us cycles from the internal
   * timer of a master. */
  write_reg(chip, MCLKDIV, 31);
  write_reg(chip, TSCYC0, 1000);
  write_reg(chip, TDIVCLK, 100);
  write_reg(chip, DTDIVCLK, 250);
  write_reg(chip, DIVCTRL, 3);
  write_reg(chip, SERMODE, REGMODE);

  /* Four cycles start at 0, 1000, 2000 and 3000 us; stop after the fourth's last pulse. */
  run_for(sim, 3700 * US);
  printf("DIV_CLK mode 0: %d pulses in 4 cycles, first at %lld ns\n", s.divclk_rises,
         (long long)(s.divclk_first_rise / 1000));
  check(s.divclk_rises == 12, "DIV_CLK mode 0 gives NDIVCLK = 3 pulses per cycle");

  s.divclk_rises = 0;
  write_reg(chip, DIVCTRL, DIVCLKMODE | 2);
  /* Mode 1 takes effect at the next cycle start (4000 us): pulses in the cycles from 4000
   * and 6000 us. */
  run_for(sim, 4000 * US);
  printf("DIV_CLK mode 1: %d pulses in 4 cycles\n", s.divclk_rises);
  check(s.divclk_rises == 2, "DIV_CLK mode 1 gives one pulse every NDIVCLK = 2 cycles");

  /* Watchdog: 500 us, output WDOGN and INT0 enabled, triggered every 200 us. */
  write_reg(chip, TWDOG, 500);
  write_reg(chip, WDCTRL, WDOG_START | WDOUT_SET | EN0_INT_WDOG);
  status = sercon_reg_read(chip, WDCTRL);
  check(status >= 0 && (status & (WDOG_START | WDOUT_SET)) == (WDOG_START | WDOUT_SET),
        "WDOG_STAT and WDOUT_STAT read 1 once set");
  last_trigger = sercon_sim_now_ps(sim);
  for (i = 0; i < 10; ++i) {
    run_for(sim, 200 * US);
    write_reg(chip, WDTRIG, 0x42);
    last_trigger = sercon_sim_now_ps(sim);
  }
  check(sercon_pin_get(chip, SERCON_PIN_WDOGN) == SERCON_HIGH, "no expiry while triggered");
  check(s.wdogn_fall < 0, "WDOGN stayed high while triggered");

  run_for(sim, 1000 * US);
  status = sercon_reg_read(chip, WDCTRL);
  printf("watchdog expired %lld ns after the last trigger; WDOGN low for %lld ns\n",
         (long long)((s.wdogn_fall - last_trigger) / 1000),
         (long long)((s.wdogn_rise - s.wdogn_fall) / 1000));
  check(s.wdogn_fall - last_trigger == 500 * US, "T_WDOG = (MCLKDIV + 1) * TWDOG / f_MCLK");
  check(s.wdogn_rise - s.wdogn_fall >= 2 * US && s.wdogn_rise - s.wdogn_fall <= 3 * US,
        "WDOGN active for 2 to 3 us");
  check(s.int0_rise == s.wdogn_fall, "INT0 rises when INT_WDOG is set");
  check(status >= 0 && (status & INT_WDOG) != 0, "INT_WDOG set");
  check(status >= 0 && (status & WDOG_START) == 0, "the watchdog switched itself off");

  write_reg(chip, WDCTRL, INT_WDOG); /* CLR_INT_WDOG */
  check(sercon_pin_get(chip, SERCON_PIN_INT0) == SERCON_LOW, "INT0 falls when cleared");
  status = sercon_reg_read(chip, WDCTRL);
  check(status >= 0 && (status & INT_WDOG) == 0, "INT_WDOG cleared");

  sercon_sim_free(sim);
  if (failures != 0) return 1;
  printf("watchdog_divclk: OK\n");
  return 0;
}
