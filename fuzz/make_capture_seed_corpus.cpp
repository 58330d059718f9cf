// Writes seed corpora for the capture reader fuzz targets in their input layout
// (fuzz/capture_fuzz_input.hpp): the shipped captures given on the command line, with and
// without --rate and --signal, and small captures made here from encoder lines that use
// what the shipped ones do not (VCD x/z, vectors, reals, scopes; sigrok 24 MHz, 2-byte
// samples, version 1).
// Usage: make_capture_seed_corpus vcd|sr <directory> [capture files...]
#include <zip.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "capture_fuzz_input.hpp"
#include "sercon/wire/encoder.hpp"

namespace {

namespace fs = std::filesystem;
using sercon::fuzz::make_fuzz_input;
using Bytes = std::vector<std::uint8_t>;

int written = 0;

void write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  std::ofstream out(dir / name, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ++written;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A short line: fill, an MST cycle of CP4 (MST, two ATs, an MDT), fill.
sercon::wire::LineBits sample_line() {
  sercon::wire::LineEncoder enc(true);
  enc.idle(24);
  enc.telegram(0xFF, Bytes{4});
  enc.idle(16);
  for (std::uint8_t d = 1; d <= 2; ++d) {
    enc.telegram(d, Bytes(8, static_cast<std::uint8_t>(d * 37)));
    enc.idle(16);
  }
  enc.telegram(0xFF, Bytes(16, 0x5A));
  enc.idle(24);
  return enc.take();
}

// The VCD reference names declared in `text` ($var TYPE WIDTH ID NAME ...).
std::vector<std::string> var_names(const std::string& text) {
  std::vector<std::string> names;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    if (word != "$var") continue;
    std::string type, width, id, name;
    if (in >> type >> width >> id >> name) names.push_back(name);
  }
  return names;
}

// A VCD of `line` at 4 Mbit/s, 1 ns timescale, with what real dumps carry around it.
std::string synthetic_vcd(const sercon::wire::LineBits& line) {
  std::string v =
      "$date today $end\n$version fuzz seed $end\n$comment x $end\n$timescale 1 ns $end\n"
      "$scope module top $end\n$scope module phy $end\n"
      "$var wire 1 ! rx $end\n$var wire 8 \" bus [7:0] $end\n$var real 64 # level $end\n"
      "$upscope $end\n$var reg 1 $% tx $end\n$upscope $end\n$enddefinitions $end\n"
      "$dumpvars\nx!\nb00000000 \"\nr0.5 #\n0$%\n$end\n";
  bool level = !line[0];
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == level) continue;
    level = line[i];
    v += "#" + std::to_string(i * 250) + "\n" + (level ? "1!" : "0!") + "\n";
    if (i % 40 == 0) v += "b1010 \"\nz$%\n";
  }
  v += "#" + std::to_string(line.size() * 250) + "\n";
  return v;
}

void vcd_seeds(const fs::path& dir, const std::vector<fs::path>& captures) {
  int n = 0;
  for (const fs::path& capture : captures) {
    const std::string text = read(capture);
    write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 0, "", text));
    write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 4, "", text));
    for (const std::string& name : var_names(text))
      write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 0, name, text));
  }
  const std::string made = synthetic_vcd(sample_line());
  write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 0, "rx", made));
  write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 4, "top.phy.rx", made));
  write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 0, "", made));     // several 1-bit
  write(dir, "vcd-" + std::to_string(n++), make_fuzz_input(0, 0, "bus", made));  // 8 bits
}

// The entries of a session file, as the structured mode's parts: version, metadata, logic.
std::vector<std::string> session_parts(const fs::path& file) {
  std::vector<std::string> parts;
  int error = 0;
  zip_t* archive = zip_open(file.c_str(), ZIP_RDONLY, &error);
  if (archive == nullptr) return parts;
  const auto entry = [&](const std::string& name, std::string& out) {
    zip_file_t* f = zip_fopen(archive, name.c_str(), 0);
    if (f == nullptr) return false;
    char buffer[4096];
    zip_int64_t n = 0;
    while ((n = zip_fread(f, buffer, sizeof buffer)) > 0)
      out.append(buffer, static_cast<std::size_t>(n));
    zip_fclose(f);
    return true;
  };
  std::string text;
  if (entry("version", text)) parts.push_back(text);
  if (entry("metadata", text = "")) parts.push_back(text);
  for (int i = 1; entry("logic-1-" + std::to_string(i), text = ""); ++i) parts.push_back(text);
  zip_discard(archive);
  return parts;
}

std::string metadata(const std::string& samplerate, const std::vector<std::string>& probes,
                     unsigned unitsize) {
  std::string text = "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\n";
  text += "total probes=" + std::to_string(probes.size()) + "\nsamplerate=" + samplerate +
          "\ntotal analog=0\n";
  for (std::size_t i = 0; i < probes.size(); ++i)
    text += "probe" + std::to_string(i + 1) + "=" + probes[i] + "\n";
  return text + "unitsize=" + std::to_string(unitsize) + "\n";
}

// `line` at `per_bit` samples a bit, `unitsize` bytes a sample, the level in bit `bit`.
std::string samples(const sercon::wire::LineBits& line, unsigned per_bit, unsigned unitsize,
                    unsigned bit) {
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    std::string s(unitsize, '\0');
    if (line[i]) s[bit / 8] = static_cast<char>(1U << (bit % 8));
    for (unsigned k = 0; k < per_bit; ++k) out += s;
  }
  return out;
}

void sr_seeds(const fs::path& dir, const std::vector<fs::path>& captures) {
  using namespace sercon::fuzz;
  int n = 0;
  for (const fs::path& capture : captures) {
    const std::string bytes = read(capture);
    write(dir, "sr-" + std::to_string(n++), make_fuzz_input(0, 0, "", bytes));
    write(dir, "sr-" + std::to_string(n++), make_fuzz_input(0, 4, "", bytes));
    const std::vector<std::string> parts = session_parts(capture);
    if (parts.size() < 3) continue;
    write(dir, "sr-" + std::to_string(n++),
          make_fuzz_input(kSrStructured, 0, "", join_parts(parts)));
    write(dir, "sr-" + std::to_string(n++),
          make_fuzz_input(kSrStructured | kSrStored, 4, "", join_parts(parts)));
  }
  const sercon::wire::LineBits line = sample_line();
  // 24 MHz (41 666.67 ps) at 4 Mbit/s: 6 samples a bit, in two entries.
  const std::string fx2 = samples(line, 6, 1, 0);
  write(dir, "sr-" + std::to_string(n++),
        make_fuzz_input(kSrStructured, 0, "",
                        join_parts({"2", metadata("24 MHz", {"D0"}, 1), fx2.substr(0, 1000),
                                    fx2.substr(1000)})));
  // Two-byte samples, the line on probe 10 of 16, chosen by name, with the rate.
  std::vector<std::string> probes;
  for (int i = 0; i < 16; ++i) probes.push_back("D" + std::to_string(i));
  write(dir, "sr-" + std::to_string(n++),
        make_fuzz_input(kSrStructured | kSrStored, 4, "D9",
                        join_parts({"2", metadata("40 MHz", probes, 2), samples(line, 10, 2, 9)})));
  // Version 1: one `logic-1` entry.
  write(
      dir, "sr-" + std::to_string(n++),
      make_fuzz_input(kSrStructured | kSrSingleEntry, 0, "rx",
                      join_parts({"1", metadata("16000000", {"rx"}, 1), samples(line, 4, 1, 0)})));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || (std::string(argv[1]) != "vcd" && std::string(argv[1]) != "sr")) {
    std::fprintf(stderr, "usage: %s vcd|sr <corpus directory> [capture files...]\n", argv[0]);
    return 2;
  }
  const fs::path dir = argv[2];
  fs::create_directories(dir);
  const std::vector<fs::path> captures(argv + 3, argv + argc);
  if (std::string(argv[1]) == "vcd")
    vcd_seeds(dir, captures);
  else
    sr_seeds(dir, captures);
  std::printf("wrote %d seeds to %s\n", written, dir.c_str());
  return 0;
}
