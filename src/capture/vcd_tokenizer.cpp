#include "vcd_tokenizer.hpp"

#include <utility>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

constexpr std::size_t kBlockSize = 64 * 1024;
// The widest real-world vector values are a few thousand bits; anything longer is not VCD.
constexpr std::size_t kMaxTokenLength = 1024 * 1024;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

}  // namespace

VcdTokenizer::VcdTokenizer(std::istream& in, std::string source)
    : in_(in), source_(std::move(source)), buffer_(kBlockSize) {}

bool VcdTokenizer::refill() {
  in_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  pos_ = 0;
  end_ = static_cast<std::size_t>(in_.gcount());
  return end_ > 0;
}

std::string_view VcdTokenizer::next() {
  token_.clear();
  for (;;) {
    if (pos_ == end_ && !refill()) return token_;
    const char c = buffer_[pos_];
    if (c == '\0') {
      throw CaptureError(source_ + ":" + std::to_string(line_) +
                         ": binary data (a NUL byte): this is not a VCD text file");
    }
    if (is_space(c)) {
      ++pos_;
      if (c == '\n') ++line_;
      if (!token_.empty()) return token_;
      continue;
    }
    if (token_.empty()) token_line_ = line_;
    if (token_.size() == kMaxTokenLength) {
      throw CaptureError(source_ + ":" + std::to_string(token_line_) + ": a word of more than " +
                         std::to_string(kMaxTokenLength) +
                         " characters: this is not a VCD text file");
    }
    token_ += c;
    ++pos_;
  }
}

}  // namespace sercon::capture
