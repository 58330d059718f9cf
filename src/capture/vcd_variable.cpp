#include "sercon/capture/vcd_variable.hpp"

#include <string_view>
#include <unordered_set>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

// At most kListed names: an error message stays a line or two for a file with thousands.
constexpr std::size_t kListed = 16;

std::string name_list(const std::vector<const VcdVariable*>& variables) {
  std::string out;
  for (std::size_t i = 0; i < variables.size() && i < kListed; ++i) {
    const VcdVariable* v = variables[i];
    if (!out.empty()) out += ", ";
    out += v->full_name();
    if (v->width != 1) out += " (" + std::to_string(v->width) + " bits)";
  }
  if (variables.size() > kListed) {
    out += " and " + std::to_string(variables.size() - kListed) + " more";
  }
  return out.empty() ? std::string("none") : out;
}

// Aliases ($var lines that share an identifier code) are one signal: the first of each, in
// file order.
std::vector<const VcdVariable*> distinct_ids(const std::vector<const VcdVariable*>& found) {
  std::unordered_set<std::string_view> seen;
  std::vector<const VcdVariable*> out;
  for (const VcdVariable* v : found) {
    if (seen.insert(v->id).second) out.push_back(v);
  }
  return out;
}

}  // namespace

std::string VcdVariable::full_name() const {
  return scope.empty() ? reference : scope + "." + reference;
}

bool VcdVariable::is_line_candidate() const {
  return width == 1 && type != "real" && type != "realtime" && type != "event" && type != "string";
}

const VcdVariable& select_vcd_variable(const std::vector<VcdVariable>& variables,
                                       std::string_view wanted) {
  std::vector<const VcdVariable*> candidates;
  for (const VcdVariable& v : variables) {
    if (v.is_line_candidate()) candidates.push_back(&v);
  }

  if (wanted.empty()) {
    candidates = distinct_ids(candidates);
    if (candidates.size() == 1) return *candidates.front();
    if (candidates.empty()) {
      std::vector<const VcdVariable*> all;
      for (const VcdVariable& v : variables) all.push_back(&v);
      throw CaptureError("the VCD file has no 1-bit signal to decode (signals: " + name_list(all) +
                         ")");
    }
    throw CaptureError("the VCD file has several 1-bit signals: " + name_list(candidates) +
                       "; choose one with --signal NAME");
  }

  std::vector<const VcdVariable*> matches;
  for (const VcdVariable& v : variables) {
    if (v.reference == wanted || v.full_name() == wanted) matches.push_back(&v);
  }
  matches = distinct_ids(matches);
  if (matches.empty()) {
    throw CaptureError("no signal named '" + std::string(wanted) +
                       "' in the VCD file (1-bit signals: " + name_list(candidates) + ")");
  }
  if (matches.size() > 1) {
    throw CaptureError("several signals are named '" + std::string(wanted) +
                       "': " + name_list(matches) + "; give the full name scope.name");
  }
  const VcdVariable& chosen = *matches.front();
  if (!chosen.is_line_candidate()) {
    throw CaptureError("signal '" + chosen.full_name() + "' is a " + std::to_string(chosen.width) +
                       "-bit " + chosen.type + "; decoding needs a 1-bit line signal");
  }
  return chosen;
}

}  // namespace sercon::capture
