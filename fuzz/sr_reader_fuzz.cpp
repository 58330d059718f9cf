// libFuzzer target for the sigrok session reader, with a --rate and a --signal name chosen
// by the input (fuzz/capture_fuzz_input.hpp), in two modes:
//   - raw: the bytes are the .sr file (a zip archive or not);
//   - structured (option bit 4): the bytes are the `version` entry, the `metadata` entry and
//     the logic entries, zipped here with libzip into a valid archive (stored or deflated,
//     split entries or one `logic-1`), so the fuzzer reaches the metadata parser and the
//     sample packing instead of stopping at the zip layer.
// Each file goes through capture::read_sr_file, whose channel must be well formed (rate in
// 1 Hz..1 THz, words = ceil(samples / 64), no stray bits past the last sample, both
// levels present), and through the path `sercon decode` takes (tools::load_capture, the
// line decoder), which must agree with it. Only the documented errors may escape.
#include <zip.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "capture_fuzz_common.hpp"
#include "sercon/capture/sr_reader.hpp"

namespace {

using namespace sercon;
using fuzz::check;

// Zips the parts: version, metadata, then logic entries. False when libzip refuses.
bool write_session(const std::filesystem::path& file, std::uint8_t options,
                   const std::vector<std::string_view>& parts) {
  int error = 0;
  zip_t* archive = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  check(archive != nullptr, "libzip creates the scratch archive");
  std::vector<std::string> names;
  if (!parts.empty()) names.emplace_back("version");
  if (parts.size() > 1) names.emplace_back("metadata");
  for (std::size_t i = 2; i < parts.size(); ++i)
    names.push_back((options & fuzz::kSrSingleEntry) != 0 && i == 2
                        ? std::string("logic-1")
                        : "logic-1-" + std::to_string(i - 1));
  for (std::size_t i = 0; i < names.size(); ++i) {
    // libzip reads the buffer at zip_close(); `parts` outlives it.
    zip_source_t* source = zip_source_buffer(archive, parts[i].data(), parts[i].size(), 0);
    const zip_int64_t index =
        source == nullptr ? -1 : zip_file_add(archive, names[i].c_str(), source, ZIP_FL_OVERWRITE);
    if (index < 0) {
      zip_source_free(source);
      zip_discard(archive);
      return false;
    }
    if ((options & fuzz::kSrStored) != 0)
      zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0);
  }
  if (zip_close(archive) != 0) {
    zip_discard(archive);
    return false;
  }
  return true;
}

void check_channel(const capture::SrChannel& c) {
  check(c.samplerate_hz >= 1 && c.samplerate_hz <= 1'000'000'000'000, "rate in 1 Hz..1 THz");
  check(c.sample_count >= 1, "a channel that is returned has samples");
  check(c.samples.size() == (c.sample_count + 63) / 64, "words = ceil(samples / 64)");
  if (c.sample_count % 64 != 0)
    check((c.samples.back() >> (c.sample_count % 64)) == 0, "no bits past the last sample");
  bool low = false;
  bool high = false;
  for (std::uint64_t k = 0; k < c.sample_count && !(low && high); ++k)
    ((c.samples[k / 64] >> (k % 64)) & 1U ? high : low) = true;
  check(low && high, "a channel that is returned has both levels");
  check(c.sample_period_ps ==
            static_cast<std::int64_t>((1'000'000'000'000 + c.samplerate_hz / 2) / c.samplerate_hz),
        "sample_period_ps is the rounded period");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fuzz::FuzzInput in = fuzz::parse_fuzz_input({reinterpret_cast<const char*>(data), size});
  static const fuzz::ScratchFile file(".sr");
  if ((in.options & fuzz::kSrStructured) != 0) {
    if (!write_session(file.path(), in.options, fuzz::split_parts(in.capture))) return 0;
  } else {
    file.write(in.capture);
  }

  bool reader_ok = false;
  try {
    check_channel(capture::read_sr_file(file.path(), in.signal));
    reader_ok = true;
  } catch (const capture::CaptureError&) {
  } catch (const std::exception& e) {
    fuzz::undocumented("read_sr_file", e);
  }
  bool capture_error = false;
  const bool loaded =
      fuzz::decode_path(file.path(), capture::CaptureFormat::Sr, in, &capture_error);
  check(!loaded || reader_ok, "sercon decode loaded a session that read_sr_file refused");
  check(!(reader_ok && capture_error), "sercon decode refused a session that read_sr_file read");
  return 0;
}
