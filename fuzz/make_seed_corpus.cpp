// Writes a seed corpus for decoder_fuzz: lines made by the encoder (packed levels, the
// fuzzer's input format) with good telegrams of SERCOS sizes and each error class.
// Usage: make_seed_corpus <directory>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sercon/wire/encoder.hpp"

namespace {

using Bytes = std::vector<std::uint8_t>;

void write(const std::filesystem::path& dir, const std::string& name,
           const sercon::wire::LineBits& line) {
  std::ofstream out(dir / name, std::ios::binary);
  const auto p = line.packed();
  out.write(reinterpret_cast<const char*>(p.data()), static_cast<std::streamsize>(p.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <corpus directory>\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  using sercon::wire::LineEncoder;
  int n = 0;
  for (bool level : {false, true}) {
    LineEncoder mst(level);  // MST of CP0..CP4 (sercos-facts §2)
    mst.idle(9);
    for (std::uint8_t cp = 0; cp < 5; ++cp) mst.telegram(0xFF, Bytes{cp});
    mst.idle(16);
    write(dir, "mst-" + std::to_string(n++), mst.bits());

    LineEncoder cycle(level);  // MST, four 8-byte ATs, one 32-byte MDT
    cycle.idle(8);
    cycle.telegram(0xFF, Bytes{4});
    for (std::uint8_t d = 1; d <= 4; ++d)
      cycle.telegram(d, Bytes(8, static_cast<std::uint8_t>(d * 37)));
    cycle.telegram(0xFF, Bytes(32, 0x5A));
    write(dir, "cycle-" + std::to_string(n++), cycle.bits());

    LineEncoder errors(level);  // one of each error class, then a good telegram
    errors.idle(8);
    errors.raw_frame(Bytes{0xFF, 0x00, 0x87, 0xF1});  // BadFcs
    errors.flag();
    errors.stuffed_bytes(Bytes{1, 2, 3});
    errors.raw_decoded_bits("1111111");  // Abort
    errors.idle(8);
    errors.raw_frame(Bytes{0x10, 0x20});  // TooShort
    errors.flag();
    errors.stuffed_bytes(Bytes{0xFF, 0x00, 0x87, 0xF0});
    errors.raw_decoded_bits("01");
    errors.flag();  // Misaligned
    errors.telegram(0x01, Bytes{0xFF, 0xFF});
    errors.flag();
    errors.stuffed_bytes(Bytes{0xAB});  // Truncated
    write(dir, "errors-" + std::to_string(n++), errors.bits());
  }
  std::printf("wrote %d seeds to %s\n", n, dir.c_str());
  return 0;
}
