// Read-only access to the entries of a zip file (libzip), with CaptureError on failure.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

struct zip;

namespace sercon::capture {

class ZipArchive {
 public:
  explicit ZipArchive(const std::filesystem::path& file);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  bool has(const std::string& entry) const;

  // The names of all entries, in the archive's order.
  std::vector<std::string> names() const;

  // The whole entry, refused when it is larger than `max_size` bytes.
  std::string read_small(const std::string& entry, std::size_t max_size) const;

  // Hands the entry to `sink` block by block, until the end or until `sink` returns false.
  void stream(const std::string& entry,
              const std::function<bool(std::string_view block)>& sink) const;

 private:
  std::string source_;
  zip* archive_ = nullptr;
};

}  // namespace sercon::capture
