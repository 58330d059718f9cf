/* C interface to the SERCON816 / SERCON410B model: a simulation (time in integer
 * picoseconds), chips on it, their registers, RAM and pins. Every call acts at the
 * simulation's current time; sercon_sim_run_until() lets time pass.
 *
 * Errors: functions return a negative sercon_status (or NULL) and sercon_last_error()
 * says what went wrong, in English. No call throws or aborts on bad input.
 * Ownership: a sim owns its chips and fibres. Free chips with sercon_chip_free() (which
 * frees the fibres to and from the chip too), fibres with sercon_fibre_free(), or all at
 * once with sercon_sim_free(), after which those pointers must not be used.
 * Threads: a sim and its chips belong to one thread at a time; the last error is kept
 * per thread.
 * Callbacks: a pin callback hears a change when the step that made it is done (an event,
 * a register or RAM access, a chip's reaction to a pin), one change at a time in the order
 * they happened, so it never runs inside a chip's half-done reaction.
 * A pin callback may read and write registers, RAM and pins, but must not
 * free a chip, a fibre or a sim, make a fibre or call sercon_sim_run_until(): those calls
 * are refused there (run_until returns SERCON_ERR_ARGUMENT, sercon_fibre_new NULL, the
 * frees do nothing) and set the last error. */
#ifndef SERCON_SERCON_H
#define SERCON_SERCON_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sercon_sim sercon_sim;
typedef struct sercon_chip sercon_chip;
typedef struct sercon_fibre sercon_fibre;

typedef enum sercon_status {
  SERCON_OK = 0,
  SERCON_ERR_ARGUMENT = -1,   /* NULL pointer, bad config, bad pin or level */
  SERCON_ERR_RANGE = -2,      /* address beyond the register or RAM space, time in the past */
  SERCON_ERR_PIN = -3,        /* the pin cannot be driven: an output, or driven by the chip */
  SERCON_ERR_INTERNAL = -4,   /* a failure inside the model (please report it) */
  SERCON_ERR_UNSUPPORTED = -5 /* a situation the model does not simulate, e.g. a ring
                                 where every node repeats (the message says which) */
} sercon_status;

typedef enum sercon_variant { SERCON_VARIANT_816 = 0, SERCON_VARIANT_410B = 1 } sercon_variant;

typedef enum sercon_level { SERCON_LOW = 0, SERCON_HIGH = 1, SERCON_HIGHZ = 2 } sercon_level;

/* Every signal pin of datasheet Table 1. */
typedef enum sercon_pin {
  SERCON_PIN_D0 = 0,
  SERCON_PIN_D1 = 1,
  SERCON_PIN_D2 = 2,
  SERCON_PIN_D3 = 3,
  SERCON_PIN_D4 = 4,
  SERCON_PIN_D5 = 5,
  SERCON_PIN_D6 = 6,
  SERCON_PIN_D7 = 7,
  SERCON_PIN_D8 = 8,
  SERCON_PIN_D9 = 9,
  SERCON_PIN_D10 = 10,
  SERCON_PIN_D11 = 11,
  SERCON_PIN_D12 = 12,
  SERCON_PIN_D13 = 13,
  SERCON_PIN_D14 = 14,
  SERCON_PIN_D15 = 15,
  SERCON_PIN_A0 = 16,
  SERCON_PIN_A1 = 17,
  SERCON_PIN_A2 = 18,
  SERCON_PIN_A3 = 19,
  SERCON_PIN_A4 = 20,
  SERCON_PIN_A5 = 21,
  SERCON_PIN_A6 = 22,
  SERCON_PIN_A7 = 23,
  SERCON_PIN_A8 = 24,
  SERCON_PIN_A9 = 25,
  SERCON_PIN_A10 = 26,
  SERCON_PIN_A11 = 27,
  SERCON_PIN_A12 = 28,
  SERCON_PIN_A13 = 29,
  SERCON_PIN_A14 = 30,
  SERCON_PIN_A15 = 31,
  SERCON_PIN_ALEL = 32,
  SERCON_PIN_ALEH = 33,
  SERCON_PIN_RDN = 34,
  SERCON_PIN_WRN = 35,
  SERCON_PIN_BHEN = 36,
  SERCON_PIN_MCSN0 = 37,
  SERCON_PIN_MCSN1 = 38,
  SERCON_PIN_PCSN0 = 39,
  SERCON_PIN_PCS1 = 40,
  SERCON_PIN_BUSYN = 41,
  SERCON_PIN_DMAREQR = 42,
  SERCON_PIN_DMAACKRN = 43,
  SERCON_PIN_DMAREQT = 44,
  SERCON_PIN_DMAACKTN = 45,
  SERCON_PIN_ADMUX = 46,
  SERCON_PIN_BUSMODE0 = 47,
  SERCON_PIN_BUSMODE1 = 48,
  SERCON_PIN_BUSWIDTH = 49,
  SERCON_PIN_BYTEDIR = 50,
  SERCON_PIN_INT0 = 51,
  SERCON_PIN_INT1 = 52,
  SERCON_PIN_SBAUD16 = 53,
  SERCON_PIN_SBAUD = 54,
  SERCON_PIN_RXD = 55,
  SERCON_PIN_RXC = 56,
  SERCON_PIN_RECACTN = 57,
  SERCON_PIN_TXD1 = 58,
  SERCON_PIN_TXD2 = 59,
  SERCON_PIN_TXD3 = 60,
  SERCON_PIN_TXD4 = 61,
  SERCON_PIN_TXD5 = 62,
  SERCON_PIN_TXD6 = 63,
  SERCON_PIN_TXC = 64,
  SERCON_PIN_IDLE = 65,
  SERCON_PIN_TM0 = 66,
  SERCON_PIN_TM1 = 67,
  SERCON_PIN_WDOGN = 68,
  SERCON_PIN_L_ERRN = 69,
  SERCON_PIN_CYC_CLK = 70,
  SERCON_PIN_CON_CLK = 71,
  SERCON_PIN_DIV_CLK = 72,
  SERCON_PIN_SCLK = 73,
  SERCON_PIN_SCLKO2 = 74,
  SERCON_PIN_SCLKO4 = 75,
  SERCON_PIN_MCLK = 76,
  SERCON_PIN_RSTN = 77,
  SERCON_PIN_TEST = 78,
  SERCON_PIN_OUTZ = 79,
  SERCON_PIN_NDTRO = 80,
  SERCON_PIN_COUNT = 81
} sercon_pin;

typedef struct sercon_chip_config {
  int variant;     /* sercon_variant */
  int64_t mclk_hz; /* 12..64 MHz, any whole number of Hz */
  /* SCLK, up to 64 MHz (64 MHz nominal); at least 32 MHz on the SERCON816 with
   * sbaud16 = 0 (PLL on); SCLK and SCLK / 4 must divide 1e12 (whole-picosecond periods)
   * and SCLK / 32 must be whole Hz: 64, 50, 40, 32 MHz are accepted, 48 MHz is refused
   * (docs/chip.md, "Configuration"). */
  int64_t sclk_hz;
  /* Levels (0 or 1) of the strap pins the board ties. */
  int sbaud;   /* pin 29 */
  int sbaud16; /* pin 28: 1 = 410B-compatible mode (SREGEN on the 410B, must be 1) */
  int tm0;     /* pins 30, 31: repeater reset value and test mode */
  int tm1;
  int buswidth; /* 1 = 16-bit data bus */
  int bytedir;  /* 1 = A0 = 0 addresses the high byte */
} sercon_chip_config;

/* Called after a pin changed level, at simulation time t_ps. */
typedef void (*sercon_pin_callback)(void* user, sercon_pin pin, sercon_level level, int64_t t_ps);

/* The message of the last failed call on this thread ("" if none failed yet). The
 * pointer stays valid until the next failing call on this thread: copy it to keep it. */
const char* sercon_last_error(void);

sercon_sim* sercon_sim_new(void);
void sercon_sim_free(sercon_sim* sim);            /* also frees its chips; NULL is ignored */
int64_t sercon_sim_now_ps(const sercon_sim* sim); /* negative sercon_status on error */
/* Runs every event up to t_ps and sets the clock to t_ps (t_ps >= now). */
int sercon_sim_run_until(sercon_sim* sim, int64_t t_ps);

/* Defaults: SERCON816, MCLK 32 MHz, SCLK 64 MHz, SBAUD 0, SBAUD16 0, TM0 1, TM1 1,
 * 16-bit bus, low byte first. */
void sercon_chip_config_default(sercon_chip_config* config);
/* NULL on a bad config (see sercon_last_error()). */
sercon_chip* sercon_chip_new(sercon_sim* sim, const sercon_chip_config* config);
void sercon_chip_free(sercon_chip* chip); /* NULL is ignored */

/* Word accesses as the board's µP makes them (BUSWIDTH / BYTEDIR pins). Registers: word
 * addresses 0x00..0x3F (0x2B..0x3F read 0); RAM: below 2048 (816) or 1024 (410B).
 * Reads return the value 0..0xFFFF, or a negative sercon_status. */
int32_t sercon_reg_read(sercon_chip* chip, uint32_t word_addr);
int sercon_reg_write(sercon_chip* chip, uint32_t word_addr, uint16_t value);
int32_t sercon_ram_read(sercon_chip* chip, uint32_t word_addr);
int sercon_ram_write(sercon_chip* chip, uint32_t word_addr, uint16_t value);

/* Drives an input pin (or a data / address line the chip does not drive). */
int sercon_pin_set(sercon_chip* chip, int pin, int level);
/* The pin's level (a sercon_level), or a negative sercon_status. */
int sercon_pin_get(const sercon_chip* chip, int pin);
/* Calls callback(user, ...) on every change of the pin until the chip is freed. */
int sercon_on_pin_change(sercon_chip* chip, int pin, sercon_pin_callback callback, void* user);

/* Serial bit rate in bit/s (also the TxC / RxC frequency), from the pins and register
 * 0x01; 0 while OUTZ = 1. Negative sercon_status on error. */
int64_t sercon_bit_rate(const sercon_chip* chip);

/* Fibres (docs/serial-and-ring.md, "Fibre"): chips talk to each other through them. A
 * fibre carries what TxD pin `txd` (1..6) of `from` sends to the RxD of `to`, after
 * round(length_m * 5000) ps (light travels 1 m of fibre in about 5 ns). A ring is a
 * master and its slaves joined in a loop: master TxD1 -> slave 1, slave 1 TxD1 -> slave 2,
 * ..., last slave TxD1 -> master; the lines come up through the registers (0x02 TXOE bit 0
 * and TXLIGHT, 0x01 REPON in the slaves). `from` and `to` must be chips of one sim (the
 * same chip makes a loopback). NULL (see sercon_last_error()) for a NULL chip, chips of
 * two sims, a pin outside 1..6 or one that already feeds a fibre, an RxD that already
 * has one, or a length that is negative, not finite or longer than 1000 s of light. */
sercon_fibre* sercon_fibre_new(sercon_chip* from, int txd, sercon_chip* to, double length_m);
/* Frees the fibre: the RxD it fed goes dark at once (its signal is missing), and the TxD
 * pin feeds nothing. NULL is ignored. */
void sercon_fibre_free(sercon_fibre* fibre);
/* The propagation delay in ps, or a negative sercon_status. */
int64_t sercon_fibre_delay_ps(const sercon_fibre* fibre);
/* Breaks the fibre at t_ps (>= now; at once when t_ps is now, or inside a pin callback
 * right after the event that called it): the far end is dark from then on, a telegram
 * crossing it is cut there. Restored at t_ps, the far end gets what arrives from then on
 * (a telegram half-way through counts as the idle fill after it). SERCON_ERR_RANGE for a
 * time in the past. */
int sercon_fibre_break(sercon_fibre* fibre, int64_t t_ps);
int sercon_fibre_restore(sercon_fibre* fibre, int64_t t_ps);
/* 1 while broken, 0 while whole, or a negative sercon_status. */
int sercon_fibre_broken(const sercon_fibre* fibre);
/* From now on each line bit of each telegram is flipped with probability p (0..1; 0: no
 * errors), drawn from a generator seeded with `seed`: the same seed, the same errors.
 * Resets the count of sercon_fibre_bit_errors(). */
int sercon_fibre_set_bit_error_rate(sercon_fibre* fibre, double p, uint64_t seed);
/* Line bits flipped since the rate was last set, or a negative sercon_status. */
int64_t sercon_fibre_bit_errors(const sercon_fibre* fibre);

#ifdef __cplusplus
}
#endif

#endif /* SERCON_SERCON_H */
