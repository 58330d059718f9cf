// Register word addresses and bits as the tests write them: spelled out from the register
// table (docs/registers.md), not derived from the model's code, so a test fails if the
// model's table moves a bit.
#pragma once

#include <cstdint>

namespace sercon::chip::register_words {

// Word addresses.
inline constexpr std::uint16_t kSerMode = 0x01;
inline constexpr std::uint16_t kSerCtrl = 0x02;
inline constexpr std::uint16_t kTpCtrl = 0x03;
inline constexpr std::uint16_t kIntStat = 0x04;
inline constexpr std::uint16_t kIntSc = 0x05;
inline constexpr std::uint16_t kIen0A = 0x06;
inline constexpr std::uint16_t kIen1A = 0x07;
inline constexpr std::uint16_t kIen0B = 0x08;
inline constexpr std::uint16_t kIen1B = 0x09;
inline constexpr std::uint16_t kPhase = 0x0A;
inline constexpr std::uint16_t kTxPort = 0x0B;
inline constexpr std::uint16_t kDmaCtrl = 0x0C;
inline constexpr std::uint16_t kLineMon = 0x0D;
inline constexpr std::uint16_t kClockDiv = 0x0E;
inline constexpr std::uint16_t kTscyc0 = 0x0F;
inline constexpr std::uint16_t kTscyc1 = 0x10;
inline constexpr std::uint16_t kTcycdel = 0x11;
inline constexpr std::uint16_t kTcnt = 0x12;
inline constexpr std::uint16_t kTcntst = 0x13;
inline constexpr std::uint16_t kTcycstart = 0x14;
inline constexpr std::uint16_t kJtscyc1 = 0x15;
inline constexpr std::uint16_t kJtscyc2 = 0x16;
inline constexpr std::uint16_t kJtrdel1 = 0x18;
inline constexpr std::uint16_t kJtrdel2 = 0x19;
inline constexpr std::uint16_t kTconclk = 0x1A;
inline constexpr std::uint16_t kWconclk = 0x1B;
inline constexpr std::uint16_t kConCtrl = 0x1C;
inline constexpr std::uint16_t kTdivclk = 0x1E;
inline constexpr std::uint16_t kDtdivclk = 0x1F;
inline constexpr std::uint16_t kDivCtrl = 0x20;
inline constexpr std::uint16_t kSlvFlags = 0x25;
inline constexpr std::uint16_t kWdCtrl = 0x28;
inline constexpr std::uint16_t kWdTrig = 0x29;
inline constexpr std::uint16_t kTwdog = 0x2A;

// SERMODE (0x01), SERCTRL (0x02), TPCTRL (0x03), SLVFLAGS (0x25).
inline constexpr std::uint16_t kRepon = 0x0008;      // 0x01 bit 3
inline constexpr std::uint16_t kRegmode = 0x0020;    // 0x01 bit 5
inline constexpr std::uint16_t kSwbaud = 0x0040;     // 0x01 bit 6
inline constexpr std::uint16_t kPresync = 0x0100;    // 0x01 bit 8
inline constexpr std::uint16_t kEntsbaud = 0x0400;   // 0x01 bit 10
inline constexpr std::uint16_t kSwbaud16 = 0x8000;   // 0x01 bit 15
inline constexpr std::uint16_t kTxd1Light = 0x0041;  // 0x02: TxD1 driven, transmitter on
inline constexpr std::uint16_t kCycpol = 0x0001;     // 0x03 bit 0
inline constexpr std::uint16_t kInt0pol = 0x0002;    // 0x03 bit 1
inline constexpr std::uint16_t kInt1pol = 0x0004;    // 0x03 bit 2
inline constexpr std::uint16_t kEntmt = 0x0100;      // 0x03 bit 8
inline constexpr std::uint16_t kFlmdtadr = 0x1000;   // 0x25 bit 12

// SERCTRL (0x02) line monitor status bits.
inline constexpr std::uint16_t kRdist = 0x1000;  // bit 12
inline constexpr std::uint16_t kFibbr = 0x2000;  // bit 13

// INTSTAT (0x04) bits.
inline constexpr std::uint16_t kIntRdist = 0x0001;     // bit 0
inline constexpr std::uint16_t kIntFibbr = 0x0002;     // bit 1
inline constexpr std::uint16_t kIntCycst = 0x0004;     // bit 2
inline constexpr std::uint16_t kIntRend = 0x0008;      // bit 3
inline constexpr std::uint16_t kIntTend = 0x0010;      // bit 4
inline constexpr std::uint16_t kIntRerr = 0x0020;      // bit 5
inline constexpr std::uint16_t kIntEndmk = 0x0040;     // bit 6
inline constexpr std::uint16_t kIntMstEarly = 0x0080;  // bit 7
inline constexpr std::uint16_t kIntMstLate = 0x0100;   // bit 8
inline constexpr std::uint16_t kIntMstMiss = 0x0200;   // bit 9
inline constexpr std::uint16_t kIntRetmst = 0x0400;    // bit 10
inline constexpr std::uint16_t kIntConclk = 0x0800;    // bit 11
inline constexpr std::uint16_t kIntDivclk = 0x1000;    // bit 12
inline constexpr std::uint16_t kIntDmaerr = 0x2000;    // bit 13
inline constexpr std::uint16_t kWindowFlags = kIntMstEarly | kIntMstLate | kIntMstMiss;

// WDCTRL (0x28) bits.
inline constexpr std::uint16_t kWdogStart = 0x0001;  // WDOG_START / WDOG_STAT
inline constexpr std::uint16_t kIntWdog = 0x0002;    // INT_WDOG / CLR_INT_WDOG
inline constexpr std::uint16_t kWdoutSet = 0x0004;   // WDOUT_SET / WDOUT_STAT
inline constexpr std::uint16_t kEn0IntWdog = 0x0008;
inline constexpr std::uint16_t kEn1IntWdog = 0x0010;
inline constexpr std::uint16_t kWdogMsten = 0x0020;
inline constexpr std::uint16_t kIntRscend = 0x0040;  // INT_RSCEND / CLR_RSCEND
inline constexpr std::uint16_t kEn0IntRscend = 0x0080;
inline constexpr std::uint16_t kEn1IntRscend = 0x0100;

// DIVCTRL (0x20) bits.
inline constexpr std::uint16_t kPoldivclk = 0x0100;   // bit 8
inline constexpr std::uint16_t kDivclkmode = 0x0200;  // bit 9

}  // namespace sercon::chip::register_words
