// The C interface (include/sercon/sercon.h): every call works on good input and returns
// an error code plus a message, never a crash or exception, on bad input.
#include "sercon/sercon.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;

struct SimAndChip {
  SimAndChip() {
    sim = sercon_sim_new();
    sercon_chip_config config;
    sercon_chip_config_default(&config);
    chip = sercon_chip_new(sim, &config);
  }
  ~SimAndChip() { sercon_sim_free(sim); }
  sercon_sim* sim = nullptr;
  sercon_chip* chip = nullptr;
};

TEST(CApi, SimulationTime) {
  sercon_sim* sim = sercon_sim_new();
  ASSERT_NE(sim, nullptr);
  EXPECT_EQ(sercon_sim_now_ps(sim), 0);
  EXPECT_EQ(sercon_sim_run_until(sim, 1'000'000), SERCON_OK);
  EXPECT_EQ(sercon_sim_now_ps(sim), 1'000'000);
  EXPECT_EQ(sercon_sim_run_until(sim, 5), SERCON_ERR_RANGE);
  EXPECT_THAT(sercon_last_error(), HasSubstr("before now"));
  sercon_sim_free(sim);
}

TEST(CApi, ChipConfigErrorsGiveNullAndAMessage) {
  sercon_sim* sim = sercon_sim_new();
  sercon_chip_config config;
  sercon_chip_config_default(&config);
  EXPECT_EQ(sercon_chip_new(sim, nullptr), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("config is NULL"));
  config.mclk_hz = 100'000'000;
  EXPECT_EQ(sercon_chip_new(sim, &config), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("MCLK"));
  sercon_chip_config_default(&config);
  config.variant = 7;
  EXPECT_EQ(sercon_chip_new(sim, &config), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("unknown variant"));
  sercon_chip_config_default(&config);
  config.tm1 = 2;
  EXPECT_EQ(sercon_chip_new(sim, &config), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("tm1"));
  sercon_chip_config_default(&config);
  config.variant = SERCON_VARIANT_410B;  // needs SREGEN (sbaud16) = 1
  EXPECT_EQ(sercon_chip_new(sim, &config), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("SREGEN"));
  config.sbaud16 = 1;
  sercon_chip* chip = sercon_chip_new(sim, &config);
  ASSERT_NE(chip, nullptr);
  EXPECT_EQ(sercon_reg_read(chip, 0), 0x0002);
  sercon_chip_free(chip);
  sercon_sim_free(sim);
}

TEST(CApi, RegistersAndRam) {
  SimAndChip s;
  ASSERT_NE(s.chip, nullptr);
  EXPECT_EQ(sercon_reg_read(s.chip, 0x00), 0x0010);
  EXPECT_EQ(sercon_reg_write(s.chip, 0x0F, 2000), SERCON_OK);
  EXPECT_EQ(sercon_reg_read(s.chip, 0x0F), 2000);
  EXPECT_EQ(sercon_ram_write(s.chip, 2047, 0xFFFF), SERCON_OK);
  EXPECT_EQ(sercon_ram_read(s.chip, 2047), 0xFFFF);
  EXPECT_EQ(sercon_reg_read(s.chip, 0x3F), 0);
}

TEST(CApi, AddressesOutOfRange) {
  SimAndChip s;
  EXPECT_EQ(sercon_reg_read(s.chip, 0x40), SERCON_ERR_RANGE);
  EXPECT_THAT(sercon_last_error(), HasSubstr("A6-1"));
  EXPECT_EQ(sercon_reg_write(s.chip, 0x40, 0), SERCON_ERR_RANGE);
  EXPECT_EQ(sercon_ram_read(s.chip, 2048), SERCON_ERR_RANGE);
  EXPECT_EQ(sercon_ram_write(s.chip, 2048, 0), SERCON_ERR_RANGE);
  EXPECT_EQ(sercon_ram_read(s.chip, 0x10000), SERCON_ERR_RANGE);
  EXPECT_EQ(sercon_reg_read(s.chip, 0xFFFFFFFFu), SERCON_ERR_RANGE);
}

TEST(CApi, Pins) {
  SimAndChip s;
  EXPECT_EQ(sercon_pin_get(s.chip, SERCON_PIN_BUSYN), SERCON_HIGH);
  EXPECT_EQ(sercon_pin_set(s.chip, SERCON_PIN_INT0, SERCON_HIGH), SERCON_ERR_PIN);
  EXPECT_THAT(sercon_last_error(), HasSubstr("INT0 is an output"));
  EXPECT_EQ(sercon_pin_set(s.chip, 999, SERCON_HIGH), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_pin_set(s.chip, -1, SERCON_HIGH), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_pin_get(s.chip, SERCON_PIN_COUNT), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_pin_set(s.chip, SERCON_PIN_SBAUD, 7), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_bit_rate(s.chip), 16'000'000);
  EXPECT_EQ(sercon_pin_set(s.chip, SERCON_PIN_SBAUD, SERCON_HIGH), SERCON_OK);
  EXPECT_EQ(sercon_bit_rate(s.chip), 8'000'000);
  EXPECT_EQ(sercon_pin_get(s.chip, SERCON_PIN_SBAUD), SERCON_HIGH);
}

struct Seen {
  sercon_pin pin;
  sercon_level level;
  int64_t t_ps;
};

void record(void* user, sercon_pin pin, sercon_level level, int64_t t_ps) {
  static_cast<std::vector<Seen>*>(user)->push_back({pin, level, t_ps});
}

TEST(CApi, PinChangeCallbacksCarryTheTime) {
  SimAndChip s;
  std::vector<Seen> seen;
  ASSERT_EQ(sercon_on_pin_change(s.chip, SERCON_PIN_WDOGN, record, &seen), SERCON_OK);
  EXPECT_EQ(sercon_on_pin_change(s.chip, SERCON_PIN_WDOGN, nullptr, &seen), SERCON_ERR_ARGUMENT);
  sercon_sim_run_until(s.sim, 12'345);
  sercon_pin_set(s.chip, SERCON_PIN_OUTZ, SERCON_HIGH);  // every output floats
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].pin, SERCON_PIN_WDOGN);
  EXPECT_EQ(seen[0].level, SERCON_HIGHZ);
  EXPECT_EQ(seen[0].t_ps, 12'345);
}

TEST(CApi, NullHandlesAreErrors) {
  EXPECT_EQ(sercon_sim_now_ps(nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_sim_run_until(nullptr, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_reg_read(nullptr, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_reg_write(nullptr, 0, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_ram_read(nullptr, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_ram_write(nullptr, 0, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_pin_set(nullptr, 0, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_pin_get(nullptr, 0), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_on_pin_change(nullptr, 0, record, nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_bit_rate(nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_chip_new(nullptr, nullptr), nullptr);
  EXPECT_THAT(sercon_last_error(), HasSubstr("NULL"));
  sercon_chip_free(nullptr);
  sercon_sim_free(nullptr);
  sercon_chip_config_default(nullptr);
}

// A freed chip leaves no event behind: the simulation runs on.
TEST(CApi, FreeingAChipKeepsTheSimulationUsable) {
  sercon_sim* sim = sercon_sim_new();
  sercon_chip_config config;
  sercon_chip_config_default(&config);
  sercon_chip* a = sercon_chip_new(sim, &config);
  sercon_chip* b = sercon_chip_new(sim, &config);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  sercon_reg_write(a, 0x0E, 31);
  sercon_reg_write(a, 0x0F, 1000);
  sercon_sim_run_until(sim, 1'000'000);
  sercon_chip_free(a);
  EXPECT_EQ(sercon_sim_run_until(sim, 10'000'000), SERCON_OK);
  EXPECT_EQ(sercon_reg_read(b, 0), 0x0010);
  sercon_sim_free(sim);  // frees b too
}

}  // namespace

namespace {

struct CallbackProbe {
  sercon_sim* sim = nullptr;
  sercon_chip* chip = nullptr;
  int run_until_status = 0;
  std::string run_until_error;
  std::string free_error;
};

}  // namespace

// sercon.h, "Callbacks": freeing from inside a pin callback, or letting time pass there,
// would pull the running event from under the scheduler; those calls are refused.
TEST(CApi, CallbacksCannotFreeOrRunTheSimulation) {
  SimAndChip s;
  CallbackProbe probe{s.sim, s.chip, 0, {}, {}};
  ASSERT_EQ(sercon_on_pin_change(
                s.chip, SERCON_PIN_RSTN,
                [](void* user, sercon_pin, sercon_level, int64_t) {
                  auto* p = static_cast<CallbackProbe*>(user);
                  p->run_until_status = sercon_sim_run_until(p->sim, sercon_sim_now_ps(p->sim) + 1);
                  p->run_until_error = sercon_last_error();
                  sercon_chip_free(p->chip);
                  p->free_error = sercon_last_error();
                  sercon_sim_free(p->sim);
                },
                &probe),
            SERCON_OK);
  ASSERT_EQ(sercon_pin_set(s.chip, SERCON_PIN_RSTN, SERCON_LOW), SERCON_OK);
  EXPECT_EQ(probe.run_until_status, SERCON_ERR_ARGUMENT);
  EXPECT_THAT(probe.run_until_error, HasSubstr("inside a pin callback"));
  EXPECT_THAT(probe.free_error, HasSubstr("sercon_chip_free: not allowed inside a pin callback"));
  // The chip and the sim are still there and usable.
  EXPECT_EQ(sercon_pin_set(s.chip, SERCON_PIN_RSTN, SERCON_HIGH), SERCON_OK);
  EXPECT_EQ(sercon_reg_read(s.chip, 0x00), 0x0010);
}
