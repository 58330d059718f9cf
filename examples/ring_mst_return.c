/* Builds a SERCOS ring through the C API, the way a master driver's developer would test
 * against virtual chips: a master and two slaves (SERCON816, 16 Mbit/s) joined by fibres
 * of 10, 20 and 30 m, the lines brought up and the master's cycle started through the
 * registers only. The master sends its MST every 100 us cycle; the slaves repeat it, so it
 * comes back to the master's RxD (RECACTN falls) and TCYCDEL holds the measured ring
 * delay (facts §5). Then the fibre into the master is broken: FIBBR rises 255 bit times
 * later (FIBBRTIM after reset), as the driver's "ring closed" check would see.
 * Prints what it saw and "ring_mst_return: OK" when every check holds (exit code 0). */
#include <stdint.h>
#include <stdio.h>

#include "sercon/sercon.h"

#define US 1000000LL /* picoseconds per microsecond */
#define BIT 62500LL  /* one bit time at 16 Mbit/s, in ps */
#define SCLK 15625LL /* one SCLK period at 64 MHz, in ps */

/* Register word addresses and bits (docs/registers.md). */
enum { SERMODE = 0x01, SERCTRL = 0x02, INTSTAT = 0x04, CLOCKDIV = 0x0E, TSCYC0 = 0x0F };
enum { TSCYC1 = 0x10, TCYCDEL = 0x11, TCNTST = 0x13, JTSCYC1 = 0x15, JTSCYC2 = 0x16 };
enum {
  REPON = 0x0008,      /* SERMODE: repeater on */
  REGMODE = 0x0020,    /* SERMODE: master */
  TXD1_LIGHT = 0x0041, /* SERCTRL: TxD1 driven (TXOE bit 0), optical transmitter on */
  FIBBR = 0x2000,      /* SERCTRL: no receive signal */
  INT_FIBBR = 0x0002   /* INTSTAT */
};

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "ring_mst_return: FAILED: %s (%s)\n", what, sercon_last_error());
    ++failures;
  }
}

static void write_reg(sercon_chip* chip, uint32_t address, uint16_t value) {
  check(sercon_reg_write(chip, address, value) == SERCON_OK, "register write");
}

static int32_t read_reg(sercon_chip* chip, uint32_t address) {
  int32_t v = sercon_reg_read(chip, address);
  check(v >= 0, "register read");
  return v;
}

/* The first falling edge of a pin (the MST leaving: IDLE; the MST back: RECACTN). */
static void first_fall(void* user, sercon_pin pin, sercon_level level, int64_t t_ps) {
  int64_t* t = (int64_t*)user;
  (void)pin;
  if (level == SERCON_LOW && *t < 0) *t = t_ps;
}

static int64_t ceil_to_sclk(int64_t t) { return (t + SCLK - 1) / SCLK * SCLK; }

int main(void) {
  static const double lengths_m[3] = {10.0, 20.0, 30.0};
  sercon_chip_config config;
  sercon_sim* sim = sercon_sim_new();
  sercon_chip* node[3];
  sercon_fibre* fibre[3];
  int64_t sent = -1, back = -1, expected, broken;
  int32_t tcycdel;
  int i;

  sercon_chip_config_default(&config); /* SERCON816, MCLK 32 MHz, SCLK 64 MHz, 16 Mbit/s */
  for (i = 0; i < 3; ++i) node[i] = sercon_chip_new(sim, &config);
  for (i = 0; i < 3; ++i) {
    /* node i's TxD1 -> node i + 1's RxD; the last slave's back to the master (node 0). */
    fibre[i] = sercon_fibre_new(node[i], 1, node[(i + 1) % 3], lengths_m[i]);
    check(fibre[i] != NULL, "fibre");
  }
  if (failures) return 1;
  check(sercon_on_pin_change(node[0], SERCON_PIN_IDLE, first_fall, &sent) == SERCON_OK, "watch");
  check(sercon_on_pin_change(node[0], SERCON_PIN_RECACTN, first_fall, &back) == SERCON_OK, "watch");

  /* Every node: line on, 1 us ticks (MCLKDIV 31, MCLKST 18), 100 us cycles, TCNTST 1.
   * Slaves repeat and expect the MST within TCNTST -/+ 5 us; the master does not repeat. */
  for (i = 0; i < 3; ++i) {
    write_reg(node[i], SERMODE, i == 0 ? 0 : REPON);
    write_reg(node[i], SERCTRL, TXD1_LIGHT);
    write_reg(node[i], CLOCKDIV, 18 << 8 | 31);
    write_reg(node[i], TSCYC0, 100);
    write_reg(node[i], TSCYC1, 100);
    write_reg(node[i], TCNTST, 1);
    if (i > 0) {
      write_reg(node[i], JTSCYC1, (uint16_t)(1 - 5));
      write_reg(node[i], JTSCYC2, 6);
    }
  }
  write_reg(node[0], SERMODE, REGMODE); /* the master's cycles begin */
  check(sercon_sim_run_until(sim, 1000 * US) == SERCON_OK, "run");

  /* Back after each fibre (5 ns per metre) and each slave's repeater (2 bit times, up to
   * the SCLK grid; docs/serial-and-ring.md "Repeater"). */
  expected = ceil_to_sclk(sent + sercon_fibre_delay_ps(fibre[0]) + 2 * BIT);
  expected = ceil_to_sclk(expected + sercon_fibre_delay_ps(fibre[1]) + 2 * BIT);
  expected += sercon_fibre_delay_ps(fibre[2]);
  tcycdel = read_reg(node[0], TCYCDEL);
  printf("MST sent at %lld ps, back at %lld ps (%lld ps round the ring); TCYCDEL = %d\n",
         (long long)sent, (long long)back, (long long)(back - sent), (int)tcycdel);
  check(sent >= 0 && back == expected, "the MST comes back after the fibres and repeaters");
  check(tcycdel > 0, "TCYCDEL measured");
  check((read_reg(node[0], SERCTRL) & FIBBR) == 0, "the ring is closed: no FIBBR");

  /* Break the fibre into the master: its RxD is dark from now on. */
  broken = sercon_sim_now_ps(sim);
  check(sercon_fibre_break(fibre[2], broken) == SERCON_OK, "break");
  check(sercon_sim_run_until(sim, broken + 255 * BIT) == SERCON_OK, "run");
  printf("fibre 2 broken at %lld ps: FIBBR %d, INT_FIBBR %d 255 bit times later\n",
         (long long)broken, (read_reg(node[0], SERCTRL) & FIBBR) != 0,
         (read_reg(node[0], INTSTAT) & INT_FIBBR) != 0);
  check((read_reg(node[0], SERCTRL) & FIBBR) != 0, "FIBBR after FIBBRTIM bit times");
  check((read_reg(node[0], INTSTAT) & INT_FIBBR) != 0, "INT_FIBBR latched");

  sercon_sim_free(sim); /* frees the chips and the fibres */
  if (failures) return 1;
  printf("ring_mst_return: OK\n");
  return 0;
}
