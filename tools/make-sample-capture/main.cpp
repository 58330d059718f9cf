// make_sample_capture: writes the sample captures the repository ships (captures/README.md).
// Deterministic: the same program always writes the same bytes.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "phase_up.hpp"
#include "sercon/capture/bits_file.hpp"

namespace {

// sigrok's binary input with one channel: a byte per sample, the level in bit 0.
void write_oversampled(const std::string& path, const sercon::wire::LineBits& bits,
                       unsigned samples_per_bit) {
  std::vector<char> samples;
  samples.reserve(bits.size() * samples_per_bit);
  for (std::size_t i = 0; i < bits.size(); ++i)
    samples.insert(samples.end(), samples_per_bit, bits[i] ? 1 : 0);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(samples.data(), static_cast<std::streamsize>(samples.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes sercon's sample SERCOS line captures (see captures/README.md)",
               "make_sample_capture"};
  std::string output;
  bool excerpt = false;
  unsigned samples_per_bit = 0;
  app.add_option("OUTPUT", output, "File to write")->required();
  app.add_flag("--excerpt", excerpt,
               "Two CP4 cycles instead of the whole phase-up (phase-up-4drives.bits)");
  app.add_option("--samples-per-bit", samples_per_bit,
                 "Write oversampled levels for sigrok-cli's binary input (a byte per sample, "
                 "level in bit 0) instead of packed line bits")
      ->check(CLI::Range(1U, 64U));
  CLI11_PARSE(app, argc, argv);

  try {
    const sercon::wire::LineBits bits =
        excerpt ? sercon::sample::cp4_excerpt() : sercon::sample::phase_up_4drives();
    if (samples_per_bit > 0) {
      write_oversampled(output, bits, samples_per_bit);
    } else {
      sercon::capture::write_bits_file(output, bits);
    }
  } catch (const std::exception& e) {
    std::cerr << "make_sample_capture: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
