#include "test_files.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sercon::testing {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("sercon-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_file(const std::filesystem::path& file, std::string_view content) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_zip(const std::filesystem::path& file,
               const std::vector<std::pair<std::string, std::string>>& entries, bool stored) {
  int error = 0;
  zip_t* archive = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (archive == nullptr) throw std::runtime_error("zip_open failed for " + file.string());
  for (const auto& [name, content] : entries) {
    // libzip reads the buffer at zip_close(); the entries outlive it.
    zip_source_t* source = zip_source_buffer(archive, content.data(), content.size(), 0);
    const zip_int64_t index =
        source == nullptr ? -1 : zip_file_add(archive, name.c_str(), source, ZIP_FL_OVERWRITE);
    if (index < 0) {
      zip_source_free(source);
      zip_discard(archive);
      throw std::runtime_error("zip_file_add failed for " + name);
    }
    const zip_int32_t method = stored ? ZIP_CM_STORE : ZIP_CM_DEFLATE;
    if (zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), method, 0) != 0) {
      zip_discard(archive);
      throw std::runtime_error("zip_set_file_compression failed for " + name);
    }
  }
  if (zip_close(archive) != 0) {
    zip_discard(archive);
    throw std::runtime_error("zip_close failed for " + file.string());
  }
}

std::string oversample(const wire::LineBits& bits, unsigned samples_per_bit, unsigned unitsize,
                       unsigned bit) {
  std::string out;
  out.reserve(bits.size() * samples_per_bit * unitsize);
  for (std::size_t i = 0; i < bits.size(); ++i) {
    std::string sample(unitsize, '\0');
    if (bits[i]) sample[bit / 8] = static_cast<char>(1U << (bit % 8));
    for (unsigned k = 0; k < samples_per_bit; ++k) out += sample;
  }
  return out;
}

std::string sr_metadata(std::string_view samplerate, const std::vector<std::string>& probes,
                        unsigned unitsize) {
  std::string text = "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\n";
  text += "total probes=" + std::to_string(probes.size()) + "\n";
  text += "samplerate=" + std::string(samplerate) + "\n";
  text += "total analog=0\n";
  for (std::size_t i = 0; i < probes.size(); ++i) {
    text += "probe" + std::to_string(i + 1) + "=" + probes[i] + "\n";
  }
  text += "unitsize=" + std::to_string(unitsize) + "\n";
  return text;
}

void write_sr(const std::filesystem::path& file, std::string_view metadata,
              const std::string& samples, std::size_t chunk) {
  std::vector<std::pair<std::string, std::string>> entries{{"version", "2"},
                                                           {"metadata", std::string(metadata)}};
  for (std::size_t at = 0, n = 1; at < samples.size(); at += chunk, ++n) {
    entries.emplace_back("logic-1-" + std::to_string(n), samples.substr(at, chunk));
  }
  write_zip(file, entries);
}

std::string vcd_for_line(const wire::LineBits& bits, std::int64_t bit_period_ps,
                         std::int64_t timescale_ps) {
  std::ostringstream out;
  out << "$date today $end\n$version sercon tests $end\n";
  const char* unit = "ps";  // VCD wants 1, 10 or 100 of a unit
  std::int64_t number = timescale_ps;
  for (const char* bigger : {"ns", "us", "ms"}) {
    if (number < 1000 || number % 1000 != 0) break;
    number /= 1000;
    unit = bigger;
  }
  out << "$timescale " << number << ' ' << unit << " $end\n";
  out << "$scope module top $end\n$var wire 1 ! rx $end\n$upscope $end\n$enddefinitions $end\n";
  const std::int64_t units_per_bit = bit_period_ps / timescale_ps;
  out << "#0\n$dumpvars\n" << (bits[0] ? '1' : '0') << "!\n$end\n";
  for (std::size_t i = 1; i < bits.size(); ++i) {
    if (bits[i] != bits[i - 1]) {
      out << '#' << static_cast<std::int64_t>(i) * units_per_bit << '\n'
          << (bits[i] ? '1' : '0') << "!\n";
    }
  }
  out << '#' << static_cast<std::int64_t>(bits.size()) * units_per_bit << '\n';
  return out.str();
}

std::string sigrok_cli() {
#ifdef SIGROK_CLI
  const std::string path = SIGROK_CLI;
  if (!path.empty() && std::filesystem::exists(path)) return path;
#endif
  return {};
}

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

std::string shell_quote(std::string_view text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace sercon::testing
