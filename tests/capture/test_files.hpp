// Helpers shared by the capture and tools tests: temporary directories and the three
// capture formats written from line bits, so every test can build its own input.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sercon/wire/line_bits.hpp"

namespace sercon::testing {

// A fresh directory under the system temp dir, removed with everything in it at the end.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void write_file(const std::filesystem::path& file, std::string_view content);
std::string read_file(const std::filesystem::path& file);

// A zip archive holding `entries` (name, content) in order, written with libzip; deflated,
// or stored (not compressed) when `stored`.
void write_zip(const std::filesystem::path& file,
               const std::vector<std::pair<std::string, std::string>>& entries,
               bool stored = false);

// `samples_per_bit` samples of each line bit, `unitsize` bytes each (little-endian), the
// level in bit `bit` and every other bit 0.
std::string oversample(const wire::LineBits& bits, unsigned samples_per_bit, unsigned unitsize = 1,
                       unsigned bit = 0);

// The metadata of a one-device sigrok session with logic probes `probes` (probe1, ...).
std::string sr_metadata(std::string_view samplerate, const std::vector<std::string>& probes,
                        unsigned unitsize = 1);

// A version 2 sigrok session: the samples split into entries logic-1-1, logic-1-2, ...
// of at most `chunk` bytes.
void write_sr(const std::filesystem::path& file, std::string_view metadata,
              const std::string& samples, std::size_t chunk = 4096);

// A VCD with one wire `rx` in scope `top`: its level at every line bit, bit i at
// i * bit_period_ps; `timescale_ps` must divide the bit period.
std::string vcd_for_line(const wire::LineBits& bits, std::int64_t bit_period_ps,
                         std::int64_t timescale_ps = 1);

// Path of sigrok-cli, or empty when it is not installed.
std::string sigrok_cli();

// Runs `command` through the shell; returns its exit status (-1 if it did not exit).
int run_command(const std::string& command);

// `text` quoted for the shell.
std::string shell_quote(std::string_view text);

}  // namespace sercon::testing
