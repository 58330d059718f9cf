// Splits a VCD stream into whitespace-separated tokens, reading it in blocks so that
// captures of any size stream through without being held in memory.
#pragma once

#include <cstddef>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace sercon::capture {

class VcdTokenizer {
 public:
  // `source` names the input in error messages.
  VcdTokenizer(std::istream& in, std::string source);

  // The next token, valid until the next call; empty at the end of the input.
  // Throws CaptureError on binary data or on a token too long to be VCD.
  std::string_view next();

  // Line (1-based) on which the last token returned starts.
  std::size_t line() const { return token_line_; }

 private:
  bool refill();

  std::istream& in_;
  std::string source_;
  std::vector<char> buffer_;
  std::size_t pos_ = 0;
  std::size_t end_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
  std::string token_;
};

}  // namespace sercon::capture
