#include "sercon/chip/register_doc.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/chip/register_map.hpp"

namespace sercon::chip {
namespace {

std::string hex(unsigned value, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, value);
  return buf;
}

std::string_view access_name(Access a) {
  switch (a) {
    case Access::R:
      return "R";
    case Access::RW:
      return "RW";
    case Access::W:
      return "W";
    case Access::W1C:
      return "W1C";
  }
  return "?";
}

std::string_view source_name(Source s) {
  switch (s) {
    case Source::Datasheet:
      return "datasheet";
    case Source::DeltaSpec:
      return "delta spec";
    case Source::Facts:
      return "facts";
    case Source::Project:
      return "**project decision**";
  }
  return "?";
}

std::string_view variants_name(Variants v) {
  switch (v) {
    case Variants::Both:
      return "both";
    case Variants::Only816:
      return "816";
    case Variants::Only410B:
      return "410B";
  }
  return "?";
}

std::string bits(unsigned lsb, unsigned width) {
  const unsigned msb = lsb + width - 1;
  return msb == lsb ? std::to_string(lsb) : std::to_string(msb) + "-" + std::to_string(lsb);
}

// Markdown table cells must not contain a bare '|'.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// One row per field and per run of unused bits, in bit order; the first row of a
// register carries its address and name.
std::vector<std::string> bit_rows(const RegisterInfo& reg) {
  std::vector<std::string> rows;
  auto unused = [&rows](unsigned lsb, unsigned width) {
    rows.push_back(bits(lsb, width) +
                   " | *unused* | R | 0 | both | datasheet | Reads 0; writes are ignored "
                   "(datasheet 4.1) |");
  };
  unsigned next = 0;  // lowest bit not yet described
  for (const BitField& f : reg.fields) {
    if (f.lsb > next) unused(next, f.lsb - next);
    const int digits = f.width > 8 ? 4 : f.width > 4 ? 2 : 1;
    rows.push_back(bits(f.lsb, f.width) + " | " + std::string(f.name) + " | " +
                   std::string(access_name(f.access)) + " | " + hex(f.reset, digits) + " | " +
                   std::string(variants_name(f.variants)) + " | " +
                   std::string(source_name(f.source)) + " | " + cell(f.meaning) + " |");
    next = std::max(next, static_cast<unsigned>(f.lsb + f.width));
  }
  if (next < 16) unused(next, 16 - next);
  return rows;
}

void register_rows(std::string& out, const RegisterInfo& reg) {
  const std::vector<std::string> rows = bit_rows(reg);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    out += i == 0 ? "| " + hex(reg.address, 2) + " | " + std::string(reg.name) + " | " : "| | | ";
    out += rows[i] + "\n";
  }
}

}  // namespace

std::string register_table_markdown() {
  std::string out(kRegisterDocBegin);
  out +=
      "\n\n| Addr | Register | Bits | Field | Access | Reset | Variants | Source | Meaning |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  for (const RegisterInfo& reg : register_map()) register_rows(out, reg);
  out += "\nFields whose definition is a project decision:\n\n";
  for (const RegisterInfo& reg : register_map()) {
    for (const BitField& f : reg.fields) {
      if (f.source != Source::Project) continue;
      out += "- " + hex(reg.address, 2) + " " + std::string(reg.name) + " bits " +
             bits(f.lsb, f.width) + " **" + std::string(f.name) + "**";
      if (f.variants != Variants::Both) out += " (" + std::string(variants_name(f.variants)) + ")";
      out += ": " + std::string(f.meaning) + "\n";
    }
  }
  out += "\n";
  out += kRegisterDocEnd;
  out += "\n";
  return out;
}

std::string replace_generated_part(std::string_view document, std::string_view generated) {
  const auto begin = document.find(kRegisterDocBegin);
  const auto end = document.find(kRegisterDocEnd);
  if (begin == std::string_view::npos || end == std::string_view::npos || end < begin) {
    throw std::invalid_argument("the document has no generated part (markers \"" +
                                std::string(kRegisterDocBegin) + "\" ... \"" +
                                std::string(kRegisterDocEnd) + "\")");
  }
  auto after = end + kRegisterDocEnd.size();
  if (after < document.size() && document[after] == '\n') ++after;
  std::string out(document.substr(0, begin));
  out += generated;
  out += document.substr(after);
  return out;
}

}  // namespace sercon::chip
