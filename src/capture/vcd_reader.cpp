#include "sercon/capture/vcd_reader.hpp"

#include <limits>
#include <string>
#include <unordered_set>

#include "sercon/capture/capture_error.hpp"
#include "sercon/capture/input_file.hpp"
#include "sercon/capture/vcd_timescale.hpp"
#include "vcd_tokenizer.hpp"

namespace sercon::capture {
namespace {

bool is_scalar_value(char c) {
  return c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z';
}

// VCD widths beyond this are not line signals and not plausible from any real tool.
constexpr std::uint32_t kMaxWidth = 1U << 24;
// Words of stray text tolerated before the first $ command.
constexpr std::size_t kMaxLeadingWords = 16;

class VcdParser {
 public:
  VcdParser(std::istream& in, std::string_view source)
      : tokens_(in, std::string(source)), source_(source) {}

  VcdTrace parse(std::string_view signal) {
    read_header();
    VcdTrace trace;
    try {
      trace.variable = select_vcd_variable(variables_, signal);
    } catch (const CaptureError& e) {
      throw CaptureError(source_ + ": " + e.what());
    }
    trace.timescale_ps = timescale_ps_;
    read_body(trace);
    check_trace(trace);
    return trace;
  }

 private:
  // The keywords of IEEE 1364 §18.2: the simulation commands, which open a section of values
  // in the body, and with the declaration commands all of them.
  static bool is_dump_command(std::string_view tok) {
    static constexpr std::string_view kDumpCommands[] = {"$dumpall", "$dumpoff", "$dumpon",
                                                         "$dumpvars"};
    for (std::string_view c : kDumpCommands) {
      if (tok == c) return true;
    }
    return false;
  }
  static bool is_command(std::string_view tok) {
    static constexpr std::string_view kDeclarationCommands[] = {
        "$comment", "$date", "$enddefinitions", "$scope", "$timescale",
        "$upscope", "$var",  "$version"};
    for (std::string_view c : kDeclarationCommands) {
      if (tok == c) return true;
    }
    return is_dump_command(tok);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw CaptureError(source_ + ":" + std::to_string(tokens_.line()) + ": " + what);
  }

  // Tokens up to the next $end. Structural commands keep them and may not contain
  // another command (a missing $end); free-text ones ($comment, $date, ...) are skipped.
  // Other words starting with '$' are kept: an identifier code may be any printable
  // character, '$' included (sigrok-cli and Icarus Verilog give the 4th signal "$").
  std::vector<std::string> until_end(const std::string& command, bool keep) {
    const std::size_t start = tokens_.line();
    std::vector<std::string> words;
    for (;;) {
      const std::string_view tok = tokens_.next();
      if (tok.empty()) {
        fail("the file ends inside " + command + " (opened at line " + std::to_string(start) +
             ", no $end)");
      }
      if (tok == "$end") return words;
      if (keep) {
        if (is_command(tok))
          fail("'" + std::string(tok) + "' inside " + command + ": missing $end");
        words.emplace_back(tok);
      }
    }
  }

  void read_header() {
    bool first = true;
    std::string leading;  // words before the first $ command
    std::size_t skipped = 0;
    for (;;) {
      const std::string_view tok = tokens_.next();
      if (tok.empty()) {
        fail(first ? (skipped > 0
                          ? "not a VCD file: no $ command in it (it starts with '" + leading + "')"
                          : std::string("the file is empty: not a VCD file"))
                   : "the file ends inside the VCD header (no $enddefinitions)");
      }
      if (tok.front() != '$') {
        // Text before the first command is tolerated: sigrok-cli 0.7.2 writes a stray
        // "META samplerate: N" line there. Anything later is an error.
        if (!first) fail("unexpected '" + printable(tok) + "' in the VCD header");
        if (skipped == 0) leading = printable(tok);
        if (++skipped > kMaxLeadingWords) {
          fail("not a VCD file: no $ command in its first " + std::to_string(kMaxLeadingWords) +
               " words (it starts with '" + leading + "')");
        }
        continue;
      }
      first = false;
      const std::string command(tok);
      const bool structural = command == "$timescale" || command == "$scope" ||
                              command == "$upscope" || command == "$var" ||
                              command == "$enddefinitions";
      const std::vector<std::string> words = until_end(command, structural);
      if (command == "$timescale") {
        read_timescale(words);
      } else if (command == "$scope") {
        if (words.empty()) fail("$scope without a name");
        scopes_.push_back(words.back());
      } else if (command == "$upscope") {
        if (scopes_.empty()) fail("$upscope without an open $scope");
        scopes_.pop_back();
      } else if (command == "$var") {
        read_var(words);
      } else if (command == "$enddefinitions") {
        break;
      }
    }
    if (timescale_ps_ == 0) fail("no $timescale in the VCD header: its times have no unit");
    if (variables_.empty()) fail("no $var in the VCD header: the file declares no signal");
  }

  void read_timescale(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& w : words) text += (text.empty() ? "" : " ") + w;
    try {
      timescale_ps_ = parse_vcd_timescale_ps(text);
    } catch (const CaptureError& e) {
      fail(e.what());
    }
  }

  void read_var(const std::vector<std::string>& words) {
    if (words.size() < 4) fail("$var needs a type, a width, an identifier code and a name");
    VcdVariable var;
    var.type = words[0];
    var.width = parse_width(words[1]);
    var.id = words[2];
    var.reference = words[3];
    for (const std::string& s : scopes_) var.scope += (var.scope.empty() ? "" : ".") + s;
    ids_.insert(var.id);
    variables_.push_back(std::move(var));
  }

  std::uint32_t parse_width(const std::string& text) const {
    std::uint64_t width = 0;
    for (char c : text) {
      if (c < '0' || c > '9' || width > kMaxWidth) fail("bad $var width '" + text + "'");
      width = width * 10 + static_cast<std::uint64_t>(c - '0');
    }
    if (text.empty() || width == 0 || width > kMaxWidth) fail("bad $var width '" + text + "'");
    return static_cast<std::uint32_t>(width);
  }

  void read_body(VcdTrace& trace) {
    bool in_dump_section = false;
    for (;;) {
      const std::string_view tok = tokens_.next();
      if (tok.empty()) break;
      const char c = tok.front();
      if (c == '#') {
        set_time(tok, trace);
      } else if (is_scalar_value(c)) {
        const std::string_view id = tok.substr(1);
        if (id.empty()) fail("value '" + std::string(tok) + "' without an identifier code");
        apply(c, id, trace);
      } else if (c == 'b' || c == 'B') {
        const std::string value(tok.substr(1));
        if (value.empty()) fail("empty vector value '" + value + "'");
        for (char v : value) {
          if (!is_scalar_value(v)) fail("bad vector value '" + std::string(tok) + "'");
        }
        apply(value.back(), identifier_after(tok), trace);
      } else if (c == 'r' || c == 'R') {
        const std::string value(tok);
        apply('x', identifier_after(value), trace);  // a real is never a line level
      } else if (is_dump_command(tok)) {
        in_dump_section = true;
      } else if (tok == "$end") {
        if (!in_dump_section) fail("$end without an open command");
        in_dump_section = false;
      } else if (tok == "$comment") {
        until_end("$comment", false);
      } else {
        fail("unexpected '" + printable(tok) + "' after $enddefinitions");
      }
    }
    trace.end_ps = have_time_ ? now_ps_ : 0;
  }

  std::string_view identifier_after(std::string_view value) {
    const std::string shown(value);
    const std::string_view id = tokens_.next();
    if (id.empty()) fail("the file ends after value '" + shown + "' (no identifier code)");
    return id;
  }

  void set_time(std::string_view tok, VcdTrace& trace) {
    const std::string_view digits = tok.substr(1);
    const std::int64_t limit = std::numeric_limits<std::int64_t>::max() / timescale_ps_;
    std::int64_t units = 0;
    for (char c : digits) {
      if (c < '0' || c > '9') fail("bad time stamp '" + std::string(tok) + "'");
      if (units > (limit - (c - '0')) / 10) {
        fail("time stamp '" + std::string(tok) + "' is too large to hold in picoseconds");
      }
      units = units * 10 + (c - '0');
    }
    if (digits.empty()) fail("time stamp '#' without a number");
    const std::int64_t t = units * timescale_ps_;
    if (have_time_ && t < now_ps_) {
      fail("time goes backwards: " + std::string(tok) + " comes after #" +
           std::to_string(now_ps_ / timescale_ps_));
    }
    if (!have_time_ && !have_value_) trace.start_ps = t;
    have_time_ = true;
    now_ps_ = t;
  }

  void apply(char value, std::string_view id, VcdTrace& trace) {
    have_value_ = true;
    if (id != trace.variable.id) {
      if (ids_.find(std::string(id)) == ids_.end()) {
        fail("unknown identifier code '" + printable(id) + "' (no $var declares it)");
      }
      return;
    }
    if (value != '0' && value != '1') {
      ++trace.unknown_values;
      return;
    }
    const bool high = value == '1';
    if (!have_level_) {
      have_level_ = true;
      first_level_ps_ = now_ps_;
      trace.initial_level = high;
      level_ = high;
      return;
    }
    if (high == level_) return;
    level_ = high;
    auto& edges = trace.edges;
    if (!edges.empty() && edges.back().time_ps == now_ps_) {
      edges.pop_back();  // changed back at the same instant: the level never showed
    } else if (edges.empty() && first_level_ps_ == now_ps_) {
      trace.initial_level = high;  // several values at the first instant: the last counts
    } else {
      edges.push_back(wire::Edge{now_ps_, high});
    }
  }

  void check_trace(const VcdTrace& trace) const {
    const std::string name = "signal '" + trace.variable.full_name() + "'";
    if (!have_level_) {
      throw CaptureError(source_ + ": " + name + " never has a known level (" +
                         (trace.unknown_values > 0 ? "only x/z values" : "no values at all") + ")");
    }
    if (trace.edges.empty()) {
      throw CaptureError(source_ + ": " + name + " has no edges: it stays " +
                         (trace.initial_level ? "high" : "low") + " for the whole capture");
    }
  }

  static std::string printable(std::string_view text) {
    std::string out;
    for (char c : text.substr(0, 40)) {
      const auto u = static_cast<unsigned char>(c);
      out += (u >= 0x20 && u < 0x7F) ? c : '?';
    }
    if (text.size() > 40) out += "...";
    return out;
  }

  VcdTokenizer tokens_;
  std::string source_;
  std::int64_t timescale_ps_ = 0;
  std::vector<std::string> scopes_;
  std::vector<VcdVariable> variables_;
  std::unordered_set<std::string> ids_;
  bool have_time_ = false;
  bool have_value_ = false;
  std::int64_t now_ps_ = 0;
  bool have_level_ = false;  // the selected signal has had a 0 or 1
  bool level_ = false;
  std::int64_t first_level_ps_ = 0;
};

}  // namespace

VcdTrace read_vcd(std::istream& in, std::string_view signal, std::string_view source) {
  return VcdParser(in, source).parse(signal);
}

VcdTrace read_vcd_file(const std::filesystem::path& file, std::string_view signal) {
  std::ifstream in = open_capture_file(file);
  return read_vcd(in, signal, file.string());
}

}  // namespace sercon::capture
