// The register table. Each field says where its definition comes from; fields marked
// Source::Project are this project's decisions where no public source speaks
// (sercos-facts §6), explained in docs/registers.md.
#include "sercon/chip/register_map.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace sercon::chip {
namespace {

using enum Access;
using enum Source;
using enum Variants;

constexpr BitField kVersion[] = {
    {"VERSION", 0, 16, R, 0x0010, Only816, DeltaSpec, "Circuit code 0x0010 (datasheet 4.1)"},
    {"VERSION", 0, 16, R, 0x0002, Only410B, DeltaSpec, "Circuit code 0x0002 (delta spec 2.11.1.1)"},
};

constexpr BitField kSerialMode[] = {
    {"RSTFL", 0, 1, RW, 1, Both, Facts,
     "Reset flag: set by every reset (RSTN, SWRST, OUTZ; the watchdog resets the µP, not the "
     "chip); the host clears it "
     "by writing 0"},
    {"SWRST", 1, 1, W, 0, Both, Facts, "Write 1: software reset (as RSTN, RAM kept); reads 0"},
    {"REPON", 3, 1, RW, 1, Only816, DeltaSpec,
     "Repeater on; reset value from TM0/TM1 (delta spec 2.3.3: 0 only when TM0=TM1=0)"},
    {"REPON", 3, 1, RW, 0, Only410B, Project, "Repeater on; off after reset on the 410B"},
    {"SREGEN", 4, 1, R, 0, Both, Project,
     "Level of pin 28 (SBAUD16 on the 816, SREGEN on the 410B)"},
    {"REGMODE", 5, 1, RW, 0, Both, Facts,
     "Controller (master) mode 1, slave mode 0 (German 'Regler'; a master driver sets it)"},
    {"SWBAUD", 6, 1, RW, 0, Both, DeltaSpec, "Software bit rate select (delta spec 2.3.1 table)"},
    {"POLRXD", 7, 1, RW, 0, Both, Facts, "RxD inverted (1): light is a low level on RxD"},
    {"PRESYNC", 8, 1, RW, 0, Both, Project,
     "Master: cycles start on CYC_CLK (1) instead of the internal TSCYC timer (0)"},
    {"POLTXD", 9, 1, RW, 0, Both, Facts, "TxD1-6 inverted (1): light is a low level on TxD"},
    {"ENTSBAUD", 10, 1, RW, 0, Both, DeltaSpec,
     "Bit rate from SWBAUD/SWBAUD16 instead of the SBAUD pin (delta spec 2.3.1)"},
    {"SBAUD", 11, 1, R, 0, Both, Project, "Level of the SBAUD pin (29)"},
    {"SWBAUD16", 15, 1, RW, 0, Only816, DeltaSpec,
     "Software bit rate select, high pair (delta spec 2.3.1 table, 1H.15)"},
};

constexpr BitField kSerialControl[] = {
    {"TXOE", 0, 6, RW, 0, Both, Project,
     "Bit n-1: TxDn driven (1) or high impedance (0) while it outputs serial data; datasheet "
     "Table 1 (individual high-Z). A high-impedance output is dark"},
    {"TXLIGHT", 6, 1, RW, 0, Both, Facts,
     "Optical transmitter on: TxD carry the line signal (1) or stay dark (0); a driver sets "
     "0x007F to switch its LED on and clears 0x0040 to switch it off"},
    {"LEDIST", 7, 1, RW, 0, Both, Project, "L_ERRN goes low while RDIST (distortion) holds"},
    {"LEMISS", 8, 1, RW, 0, Both, Project, "L_ERRN goes low while FIBBR (no signal) holds"},
    {"TMODE", 9, 3, RW, 0, Both, DeltaSpec,
     "Test mode override: TMODE2 (bit 11) = 1 takes TMODE1/TMODE0 in place of pins TM1/TM0, "
     "same coding (delta spec 2.3.3)"},
    {"RDIST", 12, 1, R, 0, Both, Facts, "Receive signal distorted"},
    {"FIBBR", 13, 1, R, 0, Both, Facts, "Fibre broken: no receive signal (ring open)"},
    {"RECACT", 14, 1, R, 0, Both, Project,
     "Receiver is inside a telegram (RECACTN pin low): opening flag to closing flag"},
};

constexpr BitField kTelegramControl[] = {
    {"CYCPOL", 0, 1, RW, 0, Both, Project, "CYC_CLK active edge: rising (0) or falling (1)"},
    {"INT0POL", 1, 1, RW, 0, Both, Project, "INT0 active high (0) or active low (1)"},
    {"INT1POL", 2, 1, RW, 0, Both, Project, "INT1 active high (0) or active low (1)"},
    {"ENTMT", 8, 1, RW, 0, Both, DeltaSpec,
     "Enable telegram transmission (3H.8); cleared by the watchdog (delta spec 2.6.2)"},
};

constexpr BitField kInterruptA[] = {
    {"INT_RDIST", 0, 1, W1C, 0, Both, Facts,
     "Receive signal became distorted (project decision: not cleared while RDIST is 1)"},
    {"INT_FIBBR", 1, 1, W1C, 0, Both, Facts,
     "Receive signal lost (fibre broken) (project decision: not cleared while FIBBR is 1)"},
    {"INT_CYCST", 2, 1, W1C, 0, Both, Project,
     "Cycle start: MST sent (master) or accepted (slave)"},
    {"INT_REND", 3, 1, W1C, 0, Both, DeltaSpec,
     "End of a receive telegram a header accepted (delta spec 2.10.2)"},
    {"INT_TEND", 4, 1, W1C, 0, Both, Project,
     "End of an own list telegram on the line (the MST has INT_CYCST)"},
    {"INT_RERR", 5, 1, W1C, 0, Both, Project,
     "A receive header recorded an error (RERR set: errored or not received)"},
    {"INT_ENDMK", 6, 1, W1C, 0, Both, Project, "End marker time TEND reached"},
    {"INT_MSTEARLY", 7, 1, W1C, 0, Both, Facts, "MST / CYC_CLK before the JTSCYC1 window"},
    {"INT_MSTLATE", 8, 1, W1C, 0, Both, Facts, "MST / CYC_CLK after the JTSCYC2 window"},
    {"INT_MSTMISS", 9, 1, W1C, 0, Both, Facts, "No MST by the end of the JTSCYC window"},
    {"INT_RETMST", 10, 1, W1C, 0, Both, Project,
     "Master: own MST came back outside JTRDEL1..JTRDEL2 (no window while JTRDEL2 = 0), or "
     "not at all"},
    {"INT_CONCLK", 11, 1, W1C, 0, Both, Project, "CON_CLK became active"},
    {"INT_DIVCLK", 12, 1, W1C, 0, Both, Project, "A DIV_CLK pulse began"},
    {"INT_DMAERR", 13, 1, W1C, 0, Both, Project, "DMA FIFO overrun or underrun"},
};

constexpr BitField kInterruptB[] = {
    {"INT_SC", 0, 8, W1C, 0, Both, Facts,
     "Bit n: service container n raised one of its interrupt bits (second W1C register, "
     "facts §5)"},
};

constexpr BitField kEnableA0[] = {
    {"IEN0A", 0, 14, RW, 0, Both, Facts, "Bit n routes INTSTAT (0x04) bit n to INT0"},
};
constexpr BitField kEnableA1[] = {
    {"IEN1A", 0, 14, RW, 0, Both, Facts, "Bit n routes INTSTAT (0x04) bit n to INT1"},
};
constexpr BitField kEnableB0[] = {
    {"IEN0B", 0, 8, RW, 0, Both, Facts, "Bit n routes INTSC (0x05) bit n to INT0"},
};
constexpr BitField kEnableB1[] = {
    {"IEN1B", 0, 8, RW, 0, Both, Facts, "Bit n routes INTSC (0x05) bit n to INT1"},
};

constexpr BitField kPhase[] = {
    {"PHAS0", 0, 8, RW, 0, Both, DeltaSpec,
     "Phase byte sent in the MST (AH.0-7); cleared by the watchdog (delta spec 2.6.2)"},
    {"PHASR", 8, 8, R, 0, Both, Project, "Data byte of the last MST received"},
};

constexpr BitField kTxPort[] = {
    {"PORTSEL", 0, 5, RW, 0, Both, Project,
     "Bit n-2: TxDn (n = 2..6) is a parallel output port (1) or serial data (0); a port pin "
     "is always driven (TXOE applies to serial data only)"},
    {"PORTVAL", 8, 5, RW, 0, Both, Project, "Bit n-2: level of TxDn in port mode"},
};

constexpr BitField kDma[] = {
    {"DMARXEN", 0, 1, RW, 0, Both, Project,
     "Receive FIFO and DMAREQR enabled; writing 0 empties the FIFO"},
    {"DMATXEN", 1, 1, RW, 0, Both, Project,
     "Transmit FIFO and DMAREQT enabled; writing 0 empties the FIFO"},
    {"TXCNT", 2, 5, R, 0, Both, Project, "Words in the transmit FIFO (0..16)"},
    {"RXCNT", 8, 5, R, 0, Both, Project, "Words in the receive FIFO (0..16)"},
};

constexpr BitField kLineMonitor[] = {
    {"RDISTLIM", 0, 8, RW, 0x0A, Both, Project,
     "Distorted edges in a row that set RDIST: edges of a signal at a bit rate other than the "
     "receiver's; an edge at the own rate clears the count and RDIST; 0 counts as 1 (a "
     "driver writes 0xFF0A)"},
    {"FIBBRTIM", 8, 8, RW, 0xFF, Both, Project,
     "Bit times without any edge after which the signal counts as missing (FIBBR); values "
     "below 8 count as 8 (idle fill has an edge every 8 bit times)"},
};

constexpr BitField kClockDivider[] = {
    {"MCLKDIV", 0, 6, RW, 0, Only816, DeltaSpec, "MCLK divider for the 1 us time base"},
    {"MCLKDIV", 0, 5, RW, 0, Only410B, DeltaSpec, "MCLK divider for the 1 us time base"},
    {"MCLKST", 8, 6, RW, 0, Only816, DeltaSpec, "Divider start value loaded at cycle start"},
    {"MCLKST", 8, 5, RW, 0, Only410B, DeltaSpec, "Divider start value loaded at cycle start"},
};

#define SERCON_WORD_REGISTER(array, name, access, source, meaning) \
  constexpr BitField array[] = {{name, 0, 16, access, 0, Both, source, meaning}};

SERCON_WORD_REGISTER(kTscyc0, "TSCYC0", RW, Facts, "Cycle time in us, phases 0..2")
SERCON_WORD_REGISTER(kTscyc1, "TSCYC1", RW, Facts, "Cycle time in us, phases 3..4")
SERCON_WORD_REGISTER(kTcycdel, "TCYCDEL", R, Facts,
                     "Master: cycle counter value when its own MST came back (ring delay)")
SERCON_WORD_REGISTER(kTcnt, "TCNT", R, Project, "The running cycle counter (us)")
SERCON_WORD_REGISTER(kTcntst, "TCNTST", RW, Facts, "Cycle counter start value at MST detection")
SERCON_WORD_REGISTER(kTcycstart, "TCYCSTART", RW, Facts,
                     "Master: us from cycle start (timer or CYC_CLK) to sending the MST")
SERCON_WORD_REGISTER(kJtscyc1, "JTSCYC1", RW, Facts, "Start of the MST / CYC_CLK window")
SERCON_WORD_REGISTER(kJtscyc2, "JTSCYC2", RW, Facts, "End of the MST / CYC_CLK window")
SERCON_WORD_REGISTER(kJtrdel1, "JTRDEL1", RW, Facts, "Start of the own-MST return window")
SERCON_WORD_REGISTER(kJtrdel2, "JTRDEL2", RW, Facts, "End of the own-MST return window")
SERCON_WORD_REGISTER(kTconclk, "TCONCLK", RW, Project, "CON_CLK active from this cycle time (us)")
SERCON_WORD_REGISTER(kWconclk, "WCONCLK", RW, Project, "CON_CLK active width (us); 0 = never")
SERCON_WORD_REGISTER(kTdivclk, "TDIVCLK", RW, DeltaSpec, "First DIV_CLK pulse, cycle time (us)")
SERCON_WORD_REGISTER(kDtdivclk, "DTDIVCLK", RW, DeltaSpec, "Distance of DIV_CLK pulses (us)")
#undef SERCON_WORD_REGISTER

// Delta spec 2.11.2: 2AH is one of the "SERCON816 NEW Control Registers".
constexpr BitField kTwdog[] = {
    {"TWDOG", 0, 16, RW, 0, Only816, DeltaSpec, "Watchdog time constant (2AH)"},
};

constexpr BitField kConClkControl[] = {
    {"POLCONCLK", 0, 1, RW, 0, Both, Project, "CON_CLK 1-active (0) or 0-active (1)"},
};

constexpr BitField kDivClkControl[] = {
    {"NDIVCLK", 0, 8, RW, 0, Both, DeltaSpec,
     "Pulses per cycle (mode 0) or cycles per pulse (mode 1); 0 = never"},
    {"POLDIVCLK", 8, 1, RW, 0, Both, DeltaSpec, "DIV_CLK 1-active (0) or 0-active (1)"},
    {"DIVCLKMODE", 9, 1, RW, 0, Only816, DeltaSpec,
     "0: N pulses in each cycle (410B); 1: one pulse every N cycles (delta spec 2.7)"},
};

constexpr BitField kSlaveFlags[] = {
    {"FLMDTADR", 12, 1, R, 0, Both, DeltaSpec,
     "Slave, CP0..2: an MDT with the own address arrived; the AT is due (delta spec 2.9; CP0 a "
     "decision)"},
};

constexpr BitField kWatchdogControl[] = {
    {"WDOG_START", 0, 1, W, 0, Only816, DeltaSpec,
     "Write 1: watchdog on. Reads WDOG_STAT: watchdog on (1) or off (0)"},
    {"INT_WDOG", 1, 1, W1C, 0, Only816, DeltaSpec,
     "Watchdog expired. Write 1 (CLR_INT_WDOG) clears it"},
    {"WDOUT_SET", 2, 1, W, 0, Only816, DeltaSpec,
     "Write 1: enable output WDOGN. Reads WDOUT_STAT (enabled 1, disabled 0)"},
    {"EN0_INT_WDOG", 3, 1, RW, 0, Only816, DeltaSpec, "INT_WDOG triggers INT0"},
    {"EN1_INT_WDOG", 4, 1, RW, 0, Only816, DeltaSpec, "INT_WDOG triggers INT1"},
    {"WDOG_MSTEN", 5, 1, RW, 0, Only816, DeltaSpec,
     "Master: every internal MST start triggers the watchdog"},
    {"INT_RSCEND", 6, 1, W1C, 0, Only816, DeltaSpec,
     "Service-container work after a receive telegram has ended. Write 1 (CLR_RSCEND) clears"},
    {"EN0_INT_RSCEND", 7, 1, RW, 0, Only816, DeltaSpec, "INT_RSCEND triggers INT0"},
    {"EN1_INT_RSCEND", 8, 1, RW, 0, Only816, DeltaSpec, "INT_RSCEND triggers INT1"},
};

constexpr BitField kWatchdogTrigger[] = {
    {"WDOG_TRIG", 0, 8, W, 0, Only816, DeltaSpec,
     "Writing 0x42 triggers the watchdog; other values do nothing; reads 0"},
};

constexpr std::span<const BitField> kNone{};

constexpr std::array<RegisterInfo, kRegisterCount> kMap = {{
    {0x00, "VERSION", kVersion},
    {0x01, "SERMODE", kSerialMode},
    {0x02, "SERCTRL", kSerialControl},
    {0x03, "TPCTRL", kTelegramControl},
    {0x04, "INTSTAT", kInterruptA},
    {0x05, "INTSC", kInterruptB},
    {0x06, "IEN0A", kEnableA0},
    {0x07, "IEN1A", kEnableA1},
    {0x08, "IEN0B", kEnableB0},
    {0x09, "IEN1B", kEnableB1},
    {0x0A, "PHASE", kPhase},
    {0x0B, "TXPORT", kTxPort},
    {0x0C, "DMACTRL", kDma},
    {0x0D, "LINEMON", kLineMonitor},
    {0x0E, "MCLKDIV", kClockDivider},
    {0x0F, "TSCYC0", kTscyc0},
    {0x10, "TSCYC1", kTscyc1},
    {0x11, "TCYCDEL", kTcycdel},
    {0x12, "TCNT", kTcnt},
    {0x13, "TCNTST", kTcntst},
    {0x14, "TCYCSTART", kTcycstart},
    {0x15, "JTSCYC1", kJtscyc1},
    {0x16, "JTSCYC2", kJtscyc2},
    {0x17, "reserved", kNone},
    {0x18, "JTRDEL1", kJtrdel1},
    {0x19, "JTRDEL2", kJtrdel2},
    {0x1A, "TCONCLK", kTconclk},
    {0x1B, "WCONCLK", kWconclk},
    {0x1C, "CONCTRL", kConClkControl},
    {0x1D, "reserved", kNone},
    {0x1E, "TDIVCLK", kTdivclk},
    {0x1F, "DTDIVCLK", kDtdivclk},
    {0x20, "DIVCTRL", kDivClkControl},
    {0x21, "reserved", kNone},
    {0x22, "reserved", kNone},
    {0x23, "reserved", kNone},
    {0x24, "reserved", kNone},
    {0x25, "SLVFLAGS", kSlaveFlags},
    {0x26, "reserved", kNone},
    {0x27, "reserved", kNone},
    {0x28, "WDCTRL", kWatchdogControl},
    {0x29, "WDTRIG", kWatchdogTrigger},
    {0x2A, "TWDOG", kTwdog},
}};

constexpr bool present_in(const BitField& field, Variant variant) {
  switch (field.variants) {
    case Both:
      return true;
    case Only816:
      return variant == Variant::Sercon816;
    case Only410B:
      return variant == Variant::Sercon410B;
  }
  return false;
}

}  // namespace

std::span<const RegisterInfo> register_map() { return kMap; }

const RegisterInfo& register_info(std::uint8_t address) {
  if (address >= kRegisterCount) {
    throw std::out_of_range("register_info: no control register at word address " +
                            std::to_string(address));
  }
  return kMap[address];
}

std::optional<BitField> find_field(std::string_view name, Variant variant) {
  for (const RegisterInfo& reg : kMap) {
    for (const BitField& field : reg.fields) {
      if (field.name == name && present_in(field, variant)) return field;
    }
  }
  return std::nullopt;
}

RegisterMasks register_masks(std::uint8_t address, Variant variant) {
  RegisterMasks masks{};
  for (const BitField& field : register_info(address).fields) {
    if (!present_in(field, variant)) continue;
    const auto mask = field.mask();
    masks.readable |= mask;
    masks.reset |= static_cast<std::uint16_t>((field.reset << field.lsb) & mask);
    switch (field.access) {
      case R:
        break;
      case RW:
        masks.writable |= mask;
        break;
      case W:
        masks.action |= mask;
        break;
      case W1C:
        masks.clearable |= mask;
        break;
    }
  }
  return masks;
}

}  // namespace sercon::chip
