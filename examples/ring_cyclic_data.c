/* Cyclic data round a SERCOS ring through the C API, the way a master or drive developer
 * sets up the telegram lists: a master and two slaves (SERCON816, 16 Mbit/s, 250 us cycle)
 * joined by 5 m fibres, every list written into DPRAM and every mode into the registers,
 * nothing else. The master runs communication phase 4 (docs/telegram-processing.md):
 *   - each slave sends its AT (status + 2 cyclic words) at T1 = 20 / 28 us of its cycle,
 *     counted from the MST it received;
 *   - the master takes each AT into a receive container (ACHK: only that slave's address)
 *     and sends one MDT to all drives (address 255) at T2 = 60 us, a record of control
 *     word + 2 cyclic words per drive;
 *   - each slave takes its own record out of the MDT by POS.
 * It changes the data on both sides, runs two cycles, and checks that every word arrived,
 * that every receive header shows VAL without RERR or NERR, and that both slaves took
 * phase 4 from the MST (PHASR). Prints what it saw and "ring_cyclic_data: OK" when every
 * check holds (exit code 0). */
#include <stdint.h>
#include <stdio.h>

#include "sercon/sercon.h"

#define US 1000000LL /* picoseconds per microsecond */
#define CYCLE_US 250
#define SLAVES 2

/* Register word addresses and bits (docs/registers.md). */
enum { SERMODE = 0x01, SERCTRL = 0x02, TPCTRL = 0x03, PHASE = 0x0A, CLOCKDIV = 0x0E };
enum { TSCYC0 = 0x0F, TSCYC1 = 0x10, TCNTST = 0x13, JTSCYC1 = 0x15, JTSCYC2 = 0x16 };
enum {
  REPON = 0x0008,      /* SERMODE: repeater on (slaves) */
  REGMODE = 0x0020,    /* SERMODE: master; its cycles begin when it is set */
  TXD1_LIGHT = 0x0041, /* SERCTRL: TxD1 driven (TXOE bit 0), optical transmitter on */
  ENTMT = 0x0100       /* TPCTRL: transmission enabled */
};

/* DPRAM (datasheet 4.2, facts §5): word 0 points at the list of phases 0..2 (COMPT0),
 * word 1 at that of phases 3..7 (COMPT1); the master counts missed MSTs in word 10. */
enum { COMPT0 = 0, COMPT1 = 1, NMSTERR = 10 };
enum { LIST = 0x040, PHASE012_END = 0x7FC };
/* Header word 0: a transmit header 0x5000 + address (send every cycle); a receive header
 * 0x0800 + address (ACHK: only this address). Bits of a receive header's word 0: */
enum { RERR = 0x2000, VAL = 0x0400 };
enum { LASTDC = 0x8000 }; /* container control word: the last container of the telegram */

/* The slave list: AT transmit header, its container, MDT receive header, its container,
 * end marker. */
enum {
  SLAVE_AT = LIST,                /* 4 words: 0x5000 + address, T1, length, next */
  SLAVE_AT_DATA = SLAVE_AT + 5,   /* after the control word: status, word 1, word 2 */
  SLAVE_MDT = SLAVE_AT + 8,       /* 5 words: 0x08FF, time, length, next, NERR */
  SLAVE_MDT_DATA = SLAVE_MDT + 7, /* after LEN and POS: control, word 1, word 2 */
  SLAVE_END = SLAVE_MDT + 10      /* 0xC000, TEND */
};
/* The master list: per slave k (1, 2) a receive header and container (10 words), the MDT
 * transmit header (4 words) with a container of 4 words per drive, end marker. */
#define MASTER_AT(k) (LIST + 10 * ((k)-1))
#define MASTER_AT_DATA(k) (MASTER_AT(k) + 7) /* status, word 1, word 2 */
#define MASTER_MDT (MASTER_AT(SLAVES + 1))
#define MASTER_MDT_DATA(k) (MASTER_MDT + 4 + 4 * ((k)-1) + 1) /* control, word 1, word 2 */
#define MASTER_END (MASTER_MDT + 4 + 4 * SLAVES)

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "ring_cyclic_data: FAILED: %s (%s)\n", what, sercon_last_error());
    ++failures;
  }
}

static void write_reg(sercon_chip* chip, uint32_t address, uint16_t value) {
  check(sercon_reg_write(chip, address, value) == SERCON_OK, "register write");
}

static void write_ram(sercon_chip* chip, uint32_t address, uint16_t value) {
  check(sercon_ram_write(chip, address, value) == SERCON_OK, "DPRAM write");
}

static uint16_t read_reg(sercon_chip* chip, uint32_t address) {
  int32_t v = sercon_reg_read(chip, address);
  check(v >= 0, "register read");
  return (uint16_t)v;
}

static uint16_t read_ram(sercon_chip* chip, uint32_t address) {
  int32_t v = sercon_ram_read(chip, address);
  check(v >= 0, "DPRAM read");
  return (uint16_t)v;
}

static void end_marker(sercon_chip* chip, uint32_t at) {
  write_ram(chip, at, 0xC000);
  write_ram(chip, at + 1, CYCLE_US - 10); /* TEND */
}

/* What every node needs: line on, 1 us ticks (MCLK 32 MHz: MCLKDIV 31, MCLKST 18; facts
 * §5 formulas), the cycle time, TCNTST = 1. */
static void program_common(sercon_chip* chip) {
  write_reg(chip, SERCTRL, TXD1_LIGHT);
  write_reg(chip, CLOCKDIV, 18 << 8 | 31);
  write_reg(chip, TSCYC0, CYCLE_US);
  write_reg(chip, TSCYC1, CYCLE_US);
  write_reg(chip, TCNTST, 1);
}

static void program_slave(sercon_chip* chip, uint16_t address) {
  write_reg(chip, SERMODE, REPON);
  program_common(chip);
  write_reg(chip, JTSCYC1, (uint16_t)(1 - 5)); /* the MST expected at TCNTST -/+ 5 us */
  write_reg(chip, JTSCYC2, 1 + 5);
  write_ram(chip, COMPT0, PHASE012_END);
  write_ram(chip, COMPT1, LIST);
  /* The AT: send every cycle at T1, 3 words, one container. */
  write_ram(chip, SLAVE_AT, (uint16_t)(0x5000 | address));
  write_ram(chip, SLAVE_AT + 1, (uint16_t)(20 + 8 * (address - 1)));
  write_ram(chip, SLAVE_AT + 2, 3);
  write_ram(chip, SLAVE_AT + 3, SLAVE_MDT);
  write_ram(chip, SLAVE_AT + 4, LASTDC | 3);
  write_ram(chip, SLAVE_AT_DATA, (uint16_t)(0x0100 | address)); /* a status word */
  write_ram(chip, SLAVE_AT_DATA + 1, 0);
  write_ram(chip, SLAVE_AT_DATA + 2, 0);
  /* The MDT: address 255 at any time (TCHK = 0), 3 words per drive; this drive's record
   * at POS = 3 (address - 1). */
  write_ram(chip, SLAVE_MDT, 0x08FF);
  write_ram(chip, SLAVE_MDT + 1, 0);
  write_ram(chip, SLAVE_MDT + 2, 3 * SLAVES);
  write_ram(chip, SLAVE_MDT + 3, SLAVE_END);
  write_ram(chip, SLAVE_MDT + 4, 0); /* NERR */
  write_ram(chip, SLAVE_MDT + 5, LASTDC | 3);
  write_ram(chip, SLAVE_MDT + 6, (uint16_t)(3 * (address - 1)));
  end_marker(chip, SLAVE_END);
  end_marker(chip, PHASE012_END);
  write_reg(chip, TPCTRL, ENTMT);
}

static void program_master(sercon_chip* chip) {
  uint16_t k;
  write_reg(chip, SERMODE, 0); /* no repeater: its telegrams must not circle for ever */
  program_common(chip);
  write_reg(chip, PHASE, 4);
  write_ram(chip, COMPT0, PHASE012_END);
  write_ram(chip, COMPT1, LIST);
  for (k = 1; k <= SLAVES; ++k) {
    write_ram(chip, MASTER_AT(k), (uint16_t)(0x0800 | k)); /* ACHK, address k */
    write_ram(chip, MASTER_AT(k) + 1, 0);                  /* any time */
    write_ram(chip, MASTER_AT(k) + 2, 3);
    write_ram(chip, MASTER_AT(k) + 3, MASTER_AT(k + 1));
    write_ram(chip, MASTER_AT(k) + 4, 0); /* NERR */
    write_ram(chip, MASTER_AT(k) + 5, LASTDC | 3);
    write_ram(chip, MASTER_AT(k) + 6, 0); /* POS */
  }
  write_ram(chip, MASTER_MDT, 0x50FF); /* to all drives, every cycle */
  write_ram(chip, MASTER_MDT + 1, 60); /* T2 */
  write_ram(chip, MASTER_MDT + 2, 3 * SLAVES);
  write_ram(chip, MASTER_MDT + 3, MASTER_END);
  for (k = 1; k <= SLAVES; ++k) {
    write_ram(chip, MASTER_MDT_DATA(k) - 1, (uint16_t)((k == SLAVES ? LASTDC : 0) | 3));
    write_ram(chip, MASTER_MDT_DATA(k), (uint16_t)(0x0400 | k)); /* a control word */
  }
  end_marker(chip, MASTER_END);
  end_marker(chip, PHASE012_END);
  write_reg(chip, TPCTRL, ENTMT);
}

static void check_header(sercon_chip* chip, uint32_t header, const char* what) {
  uint16_t word0 = read_ram(chip, header);
  check((word0 & VAL) != 0 && (word0 & RERR) == 0 && read_ram(chip, header + 4) == 0, what);
}

int main(void) {
  sercon_chip_config config;
  sercon_sim* sim = sercon_sim_new();
  sercon_chip* node[SLAVES + 1];
  uint16_t k;
  int64_t t;

  sercon_chip_config_default(&config); /* SERCON816, MCLK 32 MHz, SCLK 64 MHz, 16 Mbit/s */
  for (k = 0; k <= SLAVES; ++k) node[k] = sercon_chip_new(sim, &config);
  for (k = 0; k <= SLAVES; ++k) {
    /* node k's TxD1 -> node k + 1's RxD; the last slave's back to the master (node 0). */
    check(sercon_fibre_new(node[k], 1, node[(k + 1) % (SLAVES + 1)], 5.0) != NULL, "fibre");
  }
  if (failures) return 1;
  for (k = 1; k <= SLAVES; ++k) program_slave(node[k], k);
  program_master(node[0]);
  write_reg(node[0], SERMODE, REGMODE); /* the master's cycles begin */
  t = 10 * CYCLE_US * US;
  check(sercon_sim_run_until(sim, t) == SERCON_OK, "run");

  /* New cyclic data on both sides (the host writes into the containers) ... */
  for (k = 1; k <= SLAVES; ++k) {
    write_ram(node[k], SLAVE_AT_DATA + 1, (uint16_t)(0x1110 * k));
    write_ram(node[k], SLAVE_AT_DATA + 2, (uint16_t)(0x2220 * k));
    write_ram(node[0], MASTER_MDT_DATA(k) + 1, (uint16_t)(0xA000 | k));
    write_ram(node[0], MASTER_MDT_DATA(k) + 2, (uint16_t)(0xB000 | k));
  }
  /* ... has gone round the ring two cycles later. */
  t += 2 * CYCLE_US * US;
  check(sercon_sim_run_until(sim, t) == SERCON_OK, "run");

  for (k = 1; k <= SLAVES; ++k) {
    uint16_t at1 = read_ram(node[0], MASTER_AT_DATA(k) + 1);
    uint16_t at2 = read_ram(node[0], MASTER_AT_DATA(k) + 2);
    uint16_t mdt1 = read_ram(node[k], SLAVE_MDT_DATA + 1);
    uint16_t mdt2 = read_ram(node[k], SLAVE_MDT_DATA + 2);
    printf(
        "slave %u: AT data %04X %04X at the master, MDT data %04X %04X (control %04X), "
        "phase %u\n",
        k, at1, at2, mdt1, mdt2, read_ram(node[k], SLAVE_MDT_DATA), read_reg(node[k], PHASE) >> 8);
    check(read_ram(node[0], MASTER_AT_DATA(k)) == (0x0100 | k), "the AT's status word arrived");
    check(at1 == 0x1110 * k && at2 == 0x2220 * k, "the AT's cyclic data arrived");
    check(read_ram(node[k], SLAVE_MDT_DATA) == (0x0400 | k), "the drive took its own record");
    check(mdt1 == (0xA000 | k) && mdt2 == (0xB000 | k), "the MDT's cyclic data arrived");
    check(read_reg(node[k], PHASE) >> 8 == 4, "the slave took phase 4 from the MST (PHASR)");
    check_header(node[0], MASTER_AT(k), "master: AT header VAL, no RERR, NERR 0");
    check_header(node[k], SLAVE_MDT, "slave: MDT header VAL, no RERR, NERR 0");
  }
  check(read_ram(node[0], NMSTERR) == 0, "the master's MSTs all came back (NMSTERR 0)");

  sercon_sim_free(sim); /* frees the chips and the fibres */
  if (failures) return 1;
  printf("ring_cyclic_data: OK\n");
  return 0;
}
