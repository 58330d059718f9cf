#include "sercon/capture/sr_reader.hpp"

#include <charconv>
#include <cstdint>
#include <string_view>

#include "sercon/capture/capture_error.hpp"
#include "sercon/capture/input_file.hpp"
#include "sercon/capture/sr_metadata.hpp"
#include "zip_archive.hpp"

namespace sercon::capture {
namespace {

constexpr std::size_t kMaxMetadataSize = 64 * 1024;

std::string probe_list(const SrMetadata& meta) {
  std::string out;
  for (const SrProbe& p : meta.probes) out += (out.empty() ? "" : ", ") + p.name;
  return out;
}

const SrProbe& select_probe(const SrMetadata& meta, std::string_view wanted,
                            const std::string& source) {
  if (wanted.empty()) {
    if (meta.probes.size() == 1) return meta.probes.front();
    throw CaptureError(source + " has several logic channels: " + probe_list(meta) +
                       "; choose one with --signal NAME");
  }
  const SrProbe* found = nullptr;
  for (const SrProbe& p : meta.probes) {
    if (p.name != wanted) continue;
    if (found != nullptr) {
      throw CaptureError(source + " has several channels named '" + std::string(wanted) + "'");
    }
    found = &p;
  }
  if (found == nullptr) {
    throw CaptureError("no channel named '" + std::string(wanted) + "' in " + source +
                       " (channels: " + probe_list(meta) + ")");
  }
  return *found;
}

// N of an entry named base-N (N > 0 without a leading zero), or 0.
std::uint64_t data_entry_number(std::string_view name, const std::string& base) {
  if (name.size() <= base.size() + 1 || !name.starts_with(base) || name[base.size()] != '-') {
    return 0;
  }
  const std::string_view digits = name.substr(base.size() + 1);
  std::uint64_t n = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (error != std::errc{} || end != digits.data() + digits.size() || digits[0] == '0') return 0;
  return n;
}

// The logic data entries: version 2 splits them into capturefile-1, -2, ...; version 1
// (and some writers of version 2) use a single entry named capturefile. A numbered entry
// after a missing one means a damaged session: decoding the part before the gap would
// pass half a capture off as all of it.
std::vector<std::string> data_entries(const ZipArchive& zip, const std::string& base,
                                      const std::string& source) {
  std::vector<std::string> entries;
  for (unsigned n = 1;; ++n) {
    const std::string name = base + "-" + std::to_string(n);
    if (!zip.has(name)) break;
    entries.push_back(name);
  }
  std::uint64_t later = 0;
  for (const std::string& name : zip.names()) {
    const std::uint64_t n = data_entry_number(name, base);
    if (n > entries.size() && (later == 0 || n < later)) later = n;
  }
  if (later != 0) {
    throw CaptureError(source + ": the logic data entry '" + base + "-" +
                       std::to_string(entries.size() + 1) + "' is missing but '" + base + "-" +
                       std::to_string(later) + "' is there (a damaged session)");
  }
  if (entries.empty() && zip.has(base)) entries.push_back(base);
  return entries;
}

// Packs one bit of every `unitsize`-byte little-endian sample.
class ChannelPacker {
 public:
  ChannelPacker(unsigned unitsize, unsigned bit, std::uint64_t max_samples, SrChannel& out)
      : unitsize_(unitsize),
        byte_(bit / 8),
        mask_(static_cast<std::uint8_t>(1U << (bit % 8))),
        max_samples_(max_samples),
        out_(out) {}

  // Set when the data held more than max_samples samples; the rest was not read.
  bool too_long() const { return too_long_; }

  // False once the data holds more than max_samples samples.
  bool add(std::string_view block) {
    for (char c : block) {
      if (offset_ == byte_) {
        if (out_.sample_count == max_samples_) {
          too_long_ = true;
          return false;
        }
        push((static_cast<std::uint8_t>(c) & mask_) != 0);
      }
      if (++offset_ == unitsize_) offset_ = 0;
    }
    return true;
  }

  bool partial_sample() const { return offset_ != 0; }
  bool changes() const { return seen_low_ && seen_high_; }

 private:
  void push(bool high) {
    const std::uint64_t k = out_.sample_count++;
    if (k % 64 == 0) out_.samples.push_back(0);
    if (high) out_.samples.back() |= std::uint64_t{1} << (k % 64);
    (high ? seen_high_ : seen_low_) = true;
  }

  unsigned unitsize_;
  unsigned byte_;
  std::uint8_t mask_;
  std::uint64_t max_samples_;
  bool too_long_ = false;
  SrChannel& out_;
  unsigned offset_ = 0;
  bool seen_low_ = false;
  bool seen_high_ = false;
};

}  // namespace

SrChannel read_sr_file(const std::filesystem::path& file, std::string_view signal,
                       std::uint64_t max_samples) {
  check_readable_file(file);
  const std::string source = file.string();
  const ZipArchive zip(file);

  if (!zip.has("version") || !zip.has("metadata")) {
    throw CaptureError(source + " is a zip archive but not a sigrok session file (no '" +
                       (zip.has("version") ? "metadata" : "version") + "' entry)");
  }
  const std::string version = zip.read_small("version", 16);
  if (version != "1" && version != "2" && version != "1\n" && version != "2\n") {
    throw CaptureError(source + ": sigrok session format version '" + version +
                       "' is not supported (1 or 2)");
  }
  SrMetadata meta;
  try {
    meta = parse_sr_metadata(zip.read_small("metadata", kMaxMetadataSize));
  } catch (const CaptureError& e) {
    throw CaptureError(source + ": " + e.what());
  }
  const SrProbe& probe = select_probe(meta, signal, source);

  SrChannel channel;
  channel.name = probe.name;
  channel.samplerate_hz = meta.samplerate_hz;
  const std::uint64_t ps_per_second = 1'000'000'000'000;
  channel.sample_period_ps =
      static_cast<std::int64_t>((ps_per_second + meta.samplerate_hz / 2) / meta.samplerate_hz);

  const std::vector<std::string> entries = data_entries(zip, meta.capturefile, source);
  if (entries.empty()) {
    throw CaptureError(source + ": no logic data ('" + meta.capturefile + "-1' or '" +
                       meta.capturefile + "') in the session");
  }
  ChannelPacker packer(meta.unitsize, probe.number - 1, max_samples, channel);
  for (const std::string& entry : entries) {
    zip.stream(entry, [&](std::string_view block) { return packer.add(block); });
    if (packer.too_long()) {
      throw CaptureError(source + ": the logic data holds more than " +
                         std::to_string(max_samples) +
                         " samples, the most sercon reads from one session");
    }
  }
  if (packer.partial_sample()) {
    throw CaptureError(source + ": the logic data ends inside a sample (truncated; " +
                       std::to_string(meta.unitsize) + " bytes per sample)");
  }
  if (channel.sample_count == 0) {
    throw CaptureError(source + ": channel '" + probe.name + "' has no samples");
  }
  if (!packer.changes()) {
    const bool high = (channel.samples.front() & 1U) != 0;
    throw CaptureError(source + ": channel '" + probe.name + "' has no edges: it stays " +
                       (high ? "high" : "low") + " for all " +
                       std::to_string(channel.sample_count) + " samples");
  }
  return channel;
}

}  // namespace sercon::capture
