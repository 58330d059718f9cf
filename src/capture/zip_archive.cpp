#include "zip_archive.hpp"

#include <zip.h>

#include <memory>
#include <vector>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

struct FileCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};
using ZipFile = std::unique_ptr<zip_file_t, FileCloser>;

}  // namespace

ZipArchive::ZipArchive(const std::filesystem::path& file) : source_(file.string()) {
  int code = 0;
  archive_ = zip_open(source_.c_str(), ZIP_RDONLY, &code);
  if (archive_ == nullptr) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string reason = zip_error_strerror(&error);
    zip_error_fini(&error);
    if (code == ZIP_ER_NOZIP) {
      throw CaptureError(source_ + " is not a sigrok session file (not a zip archive)");
    }
    throw CaptureError("cannot open " + source_ + " as a zip archive: " + reason);
  }
}

ZipArchive::~ZipArchive() { zip_discard(archive_); }

bool ZipArchive::has(const std::string& entry) const {
  return zip_name_locate(archive_, entry.c_str(), 0) >= 0;
}

std::vector<std::string> ZipArchive::names() const {
  std::vector<std::string> out;
  const zip_int64_t count = zip_get_num_entries(archive_, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), 0);
    if (name != nullptr) out.emplace_back(name);
  }
  return out;
}

std::string ZipArchive::read_small(const std::string& entry, std::size_t max_size) const {
  std::string out;
  stream(entry, [&](std::string_view block) {
    if (out.size() + block.size() > max_size) {
      throw CaptureError(source_ + ": entry '" + entry + "' is larger than " +
                         std::to_string(max_size) + " bytes");
    }
    out += block;
    return true;
  });
  return out;
}

void ZipArchive::stream(const std::string& entry,
                        const std::function<bool(std::string_view block)>& sink) const {
  ZipFile file(zip_fopen(archive_, entry.c_str(), 0));
  if (!file) {
    throw CaptureError(source_ + ": cannot open entry '" + entry + "': " + zip_strerror(archive_));
  }
  std::vector<char> buffer(64 * 1024);
  for (;;) {
    const zip_int64_t n = zip_fread(file.get(), buffer.data(), buffer.size());
    if (n < 0) {
      throw CaptureError(source_ + ": cannot read entry '" + entry +
                         "': " + zip_file_strerror(file.get()));
    }
    if (n == 0 || !sink(std::string_view(buffer.data(), static_cast<std::size_t>(n)))) return;
  }
}

}  // namespace sercon::capture
