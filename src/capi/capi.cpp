// The C interface (include/sercon/sercon.h) over sim::Scheduler and chip::Chip. Every
// entry point catches every exception: errors become a status code plus a message.
#include "sercon/sercon.h"

#include <algorithm>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/pins.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/sim/model_limit.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/scoped_count.hpp"

struct sercon_chip {
  sercon_sim* sim = nullptr;
  std::unique_ptr<sercon::chip::Chip> chip;
};

struct sercon_fibre {
  sercon_sim* sim = nullptr;
  sercon_chip* from = nullptr;
  unsigned txd = 1;
  sercon_chip* to = nullptr;
  std::unique_ptr<sercon::ring::Fibre> fibre;
};

struct sercon_sim {
  sercon::sim::Scheduler scheduler;
  // Fibres reference the chips' serial units: they are let go first (release_fibres).
  std::vector<std::unique_ptr<sercon_fibre>> fibres;
  std::vector<std::unique_ptr<sercon_chip>> chips;
};

namespace {

using sercon::chip::Pin;

static_assert(SERCON_PIN_COUNT == sercon::chip::kPinCount);
static_assert(SERCON_PIN_D0 == static_cast<int>(Pin::D0));
static_assert(SERCON_PIN_A0 == static_cast<int>(Pin::A0));
static_assert(SERCON_PIN_BUSYN == static_cast<int>(Pin::BUSYN));
static_assert(SERCON_PIN_TXD1 == static_cast<int>(Pin::TxD1));
static_assert(SERCON_PIN_CYC_CLK == static_cast<int>(Pin::CYC_CLK));
static_assert(SERCON_PIN_NDTRO == static_cast<int>(Pin::NDTRO));
static_assert(SERCON_LOW == static_cast<int>(sercon::sim::Level::Low));
static_assert(SERCON_HIGH == static_cast<int>(sercon::sim::Level::High));
static_assert(SERCON_HIGHZ == static_cast<int>(sercon::sim::Level::HighZ));

thread_local std::string last_error;

int fail(sercon_status status, std::string message) {
  last_error = std::move(message);
  return status;
}

// Runs `body`; any exception becomes a status code and message. `what` names the call.
template <typename Body>
auto guarded(const char* what, Body body) -> decltype(body()) {
  using Result = decltype(body());
  try {
    return body();
  } catch (const std::out_of_range& e) {
    return static_cast<Result>(fail(SERCON_ERR_RANGE, std::string(what) + ": " + e.what()));
  } catch (const std::invalid_argument& e) {
    return static_cast<Result>(fail(SERCON_ERR_ARGUMENT, std::string(what) + ": " + e.what()));
  } catch (const sercon::sim::ModelLimit& e) {
    return static_cast<Result>(fail(SERCON_ERR_UNSUPPORTED, std::string(what) + ": " + e.what()));
  } catch (const std::exception& e) {
    return static_cast<Result>(fail(SERCON_ERR_INTERNAL, std::string(what) + ": " + e.what()));
  } catch (...) {
    return static_cast<Result>(fail(SERCON_ERR_INTERNAL, std::string(what) + ": unknown error"));
  }
}

bool valid_pin(int pin) { return pin >= 0 && pin < SERCON_PIN_COUNT; }

int bad_pin(const char* what, int pin) {
  return fail(SERCON_ERR_ARGUMENT, std::string(what) + ": no pin number " + std::to_string(pin) +
                                       " (0.." + std::to_string(SERCON_PIN_COUNT - 1) + ")");
}

int null_argument(const char* what, const char* name) {
  return fail(SERCON_ERR_ARGUMENT, std::string(what) + ": " + name + " is NULL");
}

int address_beyond(const char* what, std::uint32_t address) {
  return fail(SERCON_ERR_RANGE,
              std::string(what) + ": word address " + std::to_string(address) + " is too large");
}

}  // namespace

namespace {
// Pin callbacks run inside the scheduler's event loop: freeing the chip or the sim, or
// letting time pass, from there would pull the ground from under the running event.
thread_local int callback_depth = 0;

bool refused_in_callback(const char* what) {
  if (callback_depth == 0) return false;
  fail(SERCON_ERR_ARGUMENT, std::string(what) + ": not allowed inside a pin callback");
  return true;
}
}  // namespace

namespace {

sercon::chip::SerialUnit& serial_of(sercon_chip& chip) {
  auto* unit = chip.chip->unit<sercon::chip::SerialUnit>();
  if (unit == nullptr) throw std::logic_error("the chip has no serial unit");
  return *unit;
}

// Unhooks a fibre from both chips: the TxD pin feeds nothing, the RxD goes dark at once.
void unhook(sercon_fibre& f) {
  serial_of(*f.from).disconnect_txd(f.txd);
  f.fibre->disconnect();
}

// Frees the fibres that `pick` selects, unhooked first.
template <typename Pick>
void release_fibres(sercon_sim& sim, Pick pick) {
  auto& fibres = sim.fibres;
  for (const auto& f : fibres) {
    if (pick(*f)) unhook(*f);
  }
  std::erase_if(fibres, [&](const auto& f) { return pick(*f); });
}

}  // namespace

extern "C" {

const char* sercon_last_error(void) { return last_error.c_str(); }

sercon_sim* sercon_sim_new(void) {
  try {
    return new sercon_sim();
  } catch (...) {
    fail(SERCON_ERR_INTERNAL, "sercon_sim_new: out of memory");
    return nullptr;
  }
}

void sercon_sim_free(sercon_sim* sim) {
  if (sim == nullptr || refused_in_callback("sercon_sim_free")) return;
  guarded("sercon_sim_free", [&] {
    release_fibres(*sim, [](const sercon_fibre&) { return true; });
    return SERCON_OK;
  });
  sim->fibres.clear();
  sim->chips.clear();  // chips cancel their events before the scheduler goes
  delete sim;
}

int64_t sercon_sim_now_ps(const sercon_sim* sim) {
  if (sim == nullptr) return null_argument("sercon_sim_now_ps", "sim");
  return sim->scheduler.now();
}

int sercon_sim_run_until(sercon_sim* sim, int64_t t_ps) {
  if (sim == nullptr) return null_argument("sercon_sim_run_until", "sim");
  if (refused_in_callback("sercon_sim_run_until")) return SERCON_ERR_ARGUMENT;
  if (t_ps < sim->scheduler.now()) {
    return fail(SERCON_ERR_RANGE, "sercon_sim_run_until: " + std::to_string(t_ps) +
                                      " ps is before now (" + std::to_string(sim->scheduler.now()) +
                                      " ps)");
  }
  return guarded("sercon_sim_run_until", [&] {
    sim->scheduler.run_until(t_ps);
    return SERCON_OK;
  });
}

void sercon_chip_config_default(sercon_chip_config* config) {
  if (config == nullptr) return;
  const sercon::chip::ChipConfig d;
  config->variant = SERCON_VARIANT_816;
  config->mclk_hz = d.mclk_hz;
  config->sclk_hz = d.sclk_hz;
  config->sbaud = d.sbaud;
  config->sbaud16 = d.sbaud16;
  config->tm0 = d.tm0;
  config->tm1 = d.tm1;
  config->buswidth = d.buswidth;
  config->bytedir = d.bytedir;
}

sercon_chip* sercon_chip_new(sercon_sim* sim, const sercon_chip_config* config) {
  const char* what = "sercon_chip_new";
  if (sim == nullptr || config == nullptr) {
    null_argument(what, sim == nullptr ? "sim" : "config");
    return nullptr;
  }
  if (config->variant != SERCON_VARIANT_816 && config->variant != SERCON_VARIANT_410B) {
    fail(SERCON_ERR_ARGUMENT, std::string(what) + ": unknown variant " +
                                  std::to_string(config->variant) +
                                  " (0 = SERCON816, 1 = SERCON410B)");
    return nullptr;
  }
  const int straps[] = {config->sbaud, config->sbaud16,  config->tm0,
                        config->tm1,   config->buswidth, config->bytedir};
  const char* strap_names[] = {"sbaud", "sbaud16", "tm0", "tm1", "buswidth", "bytedir"};
  for (std::size_t i = 0; i < std::size(straps); ++i) {
    if (straps[i] != 0 && straps[i] != 1) {
      fail(SERCON_ERR_ARGUMENT, std::string(what) + ": strap " + strap_names[i] +
                                    " must be 0 or 1, not " + std::to_string(straps[i]));
      return nullptr;
    }
  }
  sercon::chip::ChipConfig c;
  c.variant = config->variant == SERCON_VARIANT_816 ? sercon::chip::Variant::Sercon816
                                                    : sercon::chip::Variant::Sercon410B;
  c.mclk_hz = config->mclk_hz;
  c.sclk_hz = config->sclk_hz;
  c.sbaud = config->sbaud == 1;
  c.sbaud16 = config->sbaud16 == 1;
  c.tm0 = config->tm0 == 1;
  c.tm1 = config->tm1 == 1;
  c.buswidth = config->buswidth == 1;
  c.bytedir = config->bytedir == 1;
  sercon_chip* made = nullptr;
  const int status = guarded(what, [&] {
    auto chip = std::make_unique<sercon_chip>();
    chip->sim = sim;
    chip->chip = std::make_unique<sercon::chip::Chip>(sim->scheduler, c);
    made = chip.get();
    sim->chips.push_back(std::move(chip));
    return SERCON_OK;
  });
  return status == SERCON_OK ? made : nullptr;
}

void sercon_chip_free(sercon_chip* chip) {
  if (chip == nullptr || refused_in_callback("sercon_chip_free")) return;
  guarded("sercon_chip_free", [&] {
    release_fibres(*chip->sim,
                   [chip](const sercon_fibre& f) { return f.from == chip || f.to == chip; });
    return SERCON_OK;
  });
  auto& chips = chip->sim->chips;
  std::erase_if(chips, [chip](const auto& owned) { return owned.get() == chip; });
}

int32_t sercon_reg_read(sercon_chip* chip, uint32_t word_addr) {
  const char* what = "sercon_reg_read";
  if (chip == nullptr) return null_argument(what, "chip");
  if (word_addr > 0xFFFF) return address_beyond(what, word_addr);
  return guarded(what, [&]() -> int32_t {
    return chip->chip->reg_read(static_cast<std::uint16_t>(word_addr));
  });
}

int sercon_reg_write(sercon_chip* chip, uint32_t word_addr, uint16_t value) {
  const char* what = "sercon_reg_write";
  if (chip == nullptr) return null_argument(what, "chip");
  if (word_addr > 0xFFFF) return address_beyond(what, word_addr);
  return guarded(what, [&] {
    chip->chip->reg_write(static_cast<std::uint16_t>(word_addr), value);
    return SERCON_OK;
  });
}

int32_t sercon_ram_read(sercon_chip* chip, uint32_t word_addr) {
  const char* what = "sercon_ram_read";
  if (chip == nullptr) return null_argument(what, "chip");
  if (word_addr > 0xFFFF) return address_beyond(what, word_addr);
  return guarded(what, [&]() -> int32_t {
    return chip->chip->ram_read(static_cast<std::uint16_t>(word_addr));
  });
}

int sercon_ram_write(sercon_chip* chip, uint32_t word_addr, uint16_t value) {
  const char* what = "sercon_ram_write";
  if (chip == nullptr) return null_argument(what, "chip");
  if (word_addr > 0xFFFF) return address_beyond(what, word_addr);
  return guarded(what, [&] {
    chip->chip->ram_write(static_cast<std::uint16_t>(word_addr), value);
    return SERCON_OK;
  });
}

int sercon_pin_set(sercon_chip* chip, int pin, int level) {
  const char* what = "sercon_pin_set";
  if (chip == nullptr) return null_argument(what, "chip");
  if (!valid_pin(pin)) return bad_pin(what, pin);
  if (level != SERCON_LOW && level != SERCON_HIGH && level != SERCON_HIGHZ) {
    return fail(SERCON_ERR_ARGUMENT, std::string(what) + ": level " + std::to_string(level) +
                                         " is not SERCON_LOW, SERCON_HIGH or SERCON_HIGHZ");
  }
  try {
    chip->chip->drive(static_cast<Pin>(pin), static_cast<sercon::sim::Level>(level));
    return SERCON_OK;
  } catch (const std::invalid_argument& e) {  // the pin's rules: an output, a clock, ...
    return fail(SERCON_ERR_PIN, std::string(what) + ": " + e.what());
  } catch (const std::exception& e) {
    return fail(SERCON_ERR_INTERNAL, std::string(what) + ": " + e.what());
  } catch (...) {
    return fail(SERCON_ERR_INTERNAL, std::string(what) + ": unknown error");
  }
}

int sercon_pin_get(const sercon_chip* chip, int pin) {
  const char* what = "sercon_pin_get";
  if (chip == nullptr) return null_argument(what, "chip");
  if (!valid_pin(pin)) return bad_pin(what, pin);
  const sercon::chip::Chip& c = *chip->chip;
  return static_cast<int>(c.pin(static_cast<Pin>(pin)).level());
}

int sercon_on_pin_change(sercon_chip* chip, int pin, sercon_pin_callback callback, void* user) {
  const char* what = "sercon_on_pin_change";
  if (chip == nullptr) return null_argument(what, "chip");
  if (callback == nullptr) return null_argument(what, "callback");
  if (!valid_pin(pin)) return bad_pin(what, pin);
  return guarded(what, [&] {
    sercon::sim::Scheduler& scheduler = chip->sim->scheduler;
    chip->chip->pin(static_cast<Pin>(pin)).watch([&scheduler, callback, user, pin](auto level) {
      const sercon::sim::ScopedCount inside(callback_depth);
      callback(user, static_cast<sercon_pin>(pin), static_cast<sercon_level>(level),
               scheduler.now());
    });
    return SERCON_OK;
  });
}

int64_t sercon_bit_rate(const sercon_chip* chip) {
  if (chip == nullptr) return null_argument("sercon_bit_rate", "chip");
  return chip->chip->serial_clocks().bit_rate_hz;
}

sercon_fibre* sercon_fibre_new(sercon_chip* from, int txd, sercon_chip* to, double length_m) {
  const char* what = "sercon_fibre_new";
  if (from == nullptr || to == nullptr) {
    null_argument(what, from == nullptr ? "from" : "to");
    return nullptr;
  }
  if (refused_in_callback(what)) return nullptr;
  if (from->sim != to->sim) {
    fail(SERCON_ERR_ARGUMENT, std::string(what) + ": the two chips belong to different sims");
    return nullptr;
  }
  const auto kTxdCount = static_cast<int>(sercon::chip::SerialUnit::kTxdCount);
  if (txd < 1 || txd > kTxdCount) {
    fail(SERCON_ERR_ARGUMENT,
         std::string(what) + ": no TxD pin " + std::to_string(txd) + " (TxD1..TxD6 are 1..6)");
    return nullptr;
  }
  sercon_sim& sim = *from->sim;
  for (const auto& f : sim.fibres) {
    if (f->from == from && f->txd == static_cast<unsigned>(txd)) {
      fail(SERCON_ERR_ARGUMENT, std::string(what) + ": TxD" + std::to_string(txd) +
                                    " of that chip feeds a fibre already (free it first)");
      return nullptr;
    }
    if (f->to == to) {
      fail(SERCON_ERR_ARGUMENT,
           std::string(what) + ": the RxD of that chip has a fibre already (free it first)");
      return nullptr;
    }
  }
  sercon_fibre* made = nullptr;
  const int status = guarded(what, [&] {
    auto f = std::make_unique<sercon_fibre>();
    f->sim = &sim;
    f->from = from;
    f->txd = static_cast<unsigned>(txd);
    f->to = to;
    f->fibre = std::make_unique<sercon::ring::Fibre>(sim.scheduler, length_m);
    sercon::chip::SerialUnit& out = serial_of(*from);
    sercon::chip::SerialUnit& in = serial_of(*to);
    sercon_fibre* const kept = f.get();
    sim.fibres.push_back(std::move(f));
    try {
      kept->fibre->connect(in.rxd());
      out.connect_txd(kept->txd, kept->fibre->input());
    } catch (...) {  // not half made: unhooked and gone
      release_fibres(sim, [kept](const sercon_fibre& x) { return &x == kept; });
      throw;
    }
    made = kept;
    return SERCON_OK;
  });
  return status == SERCON_OK ? made : nullptr;
}

void sercon_fibre_free(sercon_fibre* fibre) {
  if (fibre == nullptr || refused_in_callback("sercon_fibre_free")) return;
  guarded("sercon_fibre_free", [&] {
    release_fibres(*fibre->sim, [fibre](const sercon_fibre& f) { return &f == fibre; });
    return SERCON_OK;
  });
}

int64_t sercon_fibre_delay_ps(const sercon_fibre* fibre) {
  if (fibre == nullptr) return null_argument("sercon_fibre_delay_ps", "fibre");
  return fibre->fibre->delay();
}

namespace {

// A break or restore at t_ps: at once when it is now (inside a pin callback right after
// the running event, which may be in the middle of a chip's own change), else an event.
int switch_fibre(sercon_fibre* fibre, int64_t t_ps, bool broken, const char* what) {
  if (fibre == nullptr) return null_argument(what, "fibre");
  const sercon::sim::Time now = fibre->sim->scheduler.now();
  if (t_ps < now) {
    return fail(SERCON_ERR_RANGE, std::string(what) + ": " + std::to_string(t_ps) +
                                      " ps is before now (" + std::to_string(now) + " ps)");
  }
  return guarded(what, [&] {
    sercon::ring::Fibre& f = *fibre->fibre;
    if (t_ps == now && callback_depth == 0) {
      broken ? f.break_now() : f.restore();
    } else {
      broken ? f.break_at(t_ps) : f.restore_at(t_ps);
    }
    return SERCON_OK;
  });
}

}  // namespace

int sercon_fibre_break(sercon_fibre* fibre, int64_t t_ps) {
  return switch_fibre(fibre, t_ps, true, "sercon_fibre_break");
}

int sercon_fibre_restore(sercon_fibre* fibre, int64_t t_ps) {
  return switch_fibre(fibre, t_ps, false, "sercon_fibre_restore");
}

int sercon_fibre_broken(const sercon_fibre* fibre) {
  if (fibre == nullptr) return null_argument("sercon_fibre_broken", "fibre");
  return fibre->fibre->broken() ? 1 : 0;
}

int sercon_fibre_set_bit_error_rate(sercon_fibre* fibre, double p, uint64_t seed) {
  const char* what = "sercon_fibre_set_bit_error_rate";
  if (fibre == nullptr) return null_argument(what, "fibre");
  return guarded(what, [&] {
    fibre->fibre->set_bit_error_rate(p, seed);
    return SERCON_OK;
  });
}

int64_t sercon_fibre_bit_errors(const sercon_fibre* fibre) {
  if (fibre == nullptr) return null_argument("sercon_fibre_bit_errors", "fibre");
  return static_cast<int64_t>(fibre->fibre->bit_errors());
}

}  // extern "C"
