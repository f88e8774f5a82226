// Hand-written DBC parser (see include/vmass/can/dbc.hpp for what it accepts and reports).
//
// A cursor walks the text byte by byte, tracking line and column. Each statement starts with a
// keyword; known statements are parsed field by field, statements we do not use are skipped up
// to their ';' (respecting quoted strings), unknown keywords are skipped to the end of the line
// with a warning. After the text, a finishing pass attaches multiplexing, checks every signal
// against its message and applies attribute defaults.
#include <algorithm>
#include <bitset>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/dbc.hpp"

namespace vmass::can {

int Message::find_signal(std::string_view signal_name) const {
  for (std::size_t i = 0; i < signals.size(); ++i) {
    if (signals[i].name == signal_name) return static_cast<int>(i);
  }
  return -1;
}

int Database::find_message(std::uint32_t message_id, bool is_extended) const {
  for (std::size_t i = 0; i < messages.size(); ++i) {
    if (messages[i].id == message_id && messages[i].extended == is_extended) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int Database::find_message(std::string_view message_name) const {
  for (std::size_t i = 0; i < messages.size(); ++i) {
    if (messages[i].name == message_name) return static_cast<int>(i);
  }
  return -1;
}

std::string DbcDiagnostic::to_string() const {
  std::string s = file + ":" + std::to_string(line);
  if (column > 0) s += ":" + std::to_string(column);
  s += severity == Severity::kError ? ": error: " : ": warning: ";
  s += message;
  return s;
}

bool DbcParseResult::ok() const { return error_count() == 0; }

int DbcParseResult::error_count() const {
  return static_cast<int>(std::count_if(diagnostics.begin(), diagnostics.end(), [](const auto& d) {
    return d.severity == Severity::kError;
  }));
}

int DbcParseResult::warning_count() const {
  return static_cast<int>(diagnostics.size()) - error_count();
}

namespace {

constexpr std::string_view kIndependentSignals = "VECTOR__INDEPENDENT_SIG_MSG";

bool is_word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// cp1252 bytes 0x80..0x9F as Unicode code points (0 where cp1252 leaves the byte undefined).
constexpr std::uint16_t kCp1252High[32] = {
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

bool is_valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      extra = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      extra = 2;
    } else if (c >= 0xF0 && c <= 0xF4) {
      extra = 3;
    } else {
      return false;
    }
    if (i + static_cast<std::size_t>(extra) >= s.size()) return false;
    for (int k = 1; k <= extra; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      if ((cc & 0xC0) != 0x80) return false;
    }
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

std::string cp1252_to_utf8(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 8);
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else if (c < 0xA0) {
      const std::uint16_t cp = kCp1252High[c - 0x80];
      append_utf8(out, cp != 0 ? cp : 0xFFFD);
    } else {
      append_utf8(out, c);  // Latin-1 range maps to itself
    }
  }
  return out;
}

struct MulValEntry {
  std::uint32_t raw_id = 0;
  std::string signal;
  std::string switch_name;
  std::vector<MuxRange> ranges;
  int line = 0;
};

class Parser {
 public:
  Parser(std::string_view text, std::string_view file, const DbcParseOptions& options,
         DbcParseResult& out)
      : s_(text), file_(file), options_(options), out_(out), db_(out.database) {}

  void run() {
    if (s_.size() >= 3 && s_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
    while (!failed_) {
      skip_ws();
      if (eof()) break;
      statement_line_ = line_;
      const char c = peek();
      if (!is_word_char(c)) {
        fail("expected a keyword (VERSION, BO_, SG_, CM_, ...)");
        break;
      }
      const std::string_view kw = read_word();
      statement(kw);
    }
    finish();  // also after an error: what was loaded is checked and stays consistent
  }

 private:
  // ---------------------------------------------------------------- cursor
  bool eof() const { return pos_ >= s_.size(); }
  char peek() const { return eof() ? '\0' : s_[pos_]; }
  int column() const { return static_cast<int>(pos_ - line_start_) + 1; }
  void advance() {
    if (s_[pos_] == '\n') {
      ++line_;
      line_start_ = pos_ + 1;
    }
    ++pos_;
  }
  /// Spaces, tabs and carriage returns (CRLF files), not newlines.
  void skip_blanks() {
    while (!eof() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }
  void skip_ws() {
    while (!eof() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' || s_[pos_] == '\n' ||
                      s_[pos_] == '\f' || s_[pos_] == '\v')) {
      advance();
    }
  }
  bool at_line_end() {
    skip_blanks();
    return eof() || peek() == '\n';
  }
  std::string_view read_word() {
    const std::size_t b = pos_;
    while (!eof() && is_word_char(s_[pos_])) ++pos_;
    return s_.substr(b, pos_ - b);
  }
  /// Skips to the end of the line; a quoted string may span lines.
  void skip_line() {
    while (!eof() && peek() != '\n') {
      if (peek() == '"') {
        std::string ignored;
        if (!read_string_raw(ignored)) return;
        continue;
      }
      advance();
    }
    if (!eof()) advance();
  }
  /// Skips past the next ';' outside quoted strings.
  void skip_statement() {
    while (!eof()) {
      if (peek() == '"') {
        std::string ignored;
        if (!read_string_raw(ignored)) return;
        continue;
      }
      const char c = peek();
      advance();
      if (c == ';') return;
    }
  }

  // ---------------------------------------------------------------- diagnostics
  bool fail(const std::string& what) {
    if (failed_) return false;
    failed_ = true;
    std::string found;
    if (eof()) {
      found = "end of file";
    } else if (peek() == '\n' || peek() == '\r') {
      found = "end of line";
    } else {
      const std::size_t b = pos_;
      std::size_t e = b;
      while (e < s_.size() && e - b < 20 && s_[e] != '\n' && s_[e] != '\r') ++e;
      found = "'" + std::string(s_.substr(b, e - b)) + "'";
    }
    out_.diagnostics.push_back(
        {Severity::kError, std::string(file_), line_, column(), what + ", found " + found});
    return false;
  }
  void error_at(int line, const std::string& what) {
    out_.diagnostics.push_back({Severity::kError, std::string(file_), line, 0, what});
  }
  /// A departure from the format that we load as meant: a warning, or an error in strict mode.
  void deviation(int line, const std::string& what) {
    out_.diagnostics.push_back({options_.strict ? Severity::kError : Severity::kWarning,
                                std::string(file_), line, 0, what});
  }

  // ---------------------------------------------------------------- tokens
  bool expect(char c, const char* context) {
    skip_blanks();
    if (peek() != c) return fail(std::string("expected '") + c + "' " + context);
    advance();
    return true;
  }
  bool read_name(std::string& out, const char* what, bool newline_ok = true) {
    if (newline_ok) {
      skip_ws();
    } else {
      skip_blanks();
    }
    const int line = line_;
    if (!is_word_char(peek())) return fail(std::string("expected ") + what);
    out = std::string(read_word());
    if (is_digit(out[0])) {
      deviation(line, std::string(what) + " '" + out + "' begins with a digit");
    }
    return true;
  }
  bool read_uint(std::uint64_t& v, const char* what) {
    skip_ws();
    const std::size_t b = pos_;
    while (!eof() && is_digit(s_[pos_])) ++pos_;
    if (b == pos_) return fail(std::string("expected ") + what);
    const auto r = std::from_chars(s_.data() + b, s_.data() + pos_, v);
    if (r.ec != std::errc()) {
      pos_ = b;
      return fail(std::string(what) + " out of range");
    }
    return true;
  }
  /// Scans a decimal number ([+-]digits[.digits][e[+-]digits]) and converts it locale-free.
  bool read_double(double& v, const char* what) {
    skip_ws();
    const std::size_t b = pos_;
    std::size_t p = pos_;
    if (p < s_.size() && (s_[p] == '+' || s_[p] == '-')) ++p;
    const std::size_t digits_begin = p;
    while (p < s_.size() && is_digit(s_[p])) ++p;
    if (p < s_.size() && s_[p] == '.') {
      ++p;
      while (p < s_.size() && is_digit(s_[p])) ++p;
    }
    if (p == digits_begin || (p == digits_begin + 1 && s_[digits_begin] == '.')) {
      return fail(std::string("expected ") + what);
    }
    if (p < s_.size() && (s_[p] == 'e' || s_[p] == 'E')) {
      std::size_t q = p + 1;
      if (q < s_.size() && (s_[q] == '+' || s_[q] == '-')) ++q;
      if (q < s_.size() && is_digit(s_[q])) {
        while (q < s_.size() && is_digit(s_[q])) ++q;
        p = q;
      }
    }
    const std::size_t from = s_[b] == '+' ? b + 1 : b;
    const auto r = std::from_chars(s_.data() + from, s_.data() + p, v);
    if (r.ec != std::errc() || r.ptr != s_.data() + p) {
      return fail(std::string(what) + " is not a number");
    }
    pos_ = p;
    return true;
  }
  /// A quoted string; \" and \\ are escapes; newlines inside are kept. No encoding check.
  bool read_string_raw(std::string& out) {
    if (peek() != '"') return fail("expected '\"'");
    const int open_line = line_;
    const int open_col = column();
    advance();
    out.clear();
    while (!eof()) {
      const char c = peek();
      if (c == '"') {
        advance();
        return true;
      }
      if (c == '\\' && pos_ + 1 < s_.size() && (s_[pos_ + 1] == '"' || s_[pos_ + 1] == '\\')) {
        out += s_[pos_ + 1];
        pos_ += 2;
        continue;
      }
      if (c != '\r') out += c;
      advance();
    }
    failed_ = true;
    out_.diagnostics.push_back({Severity::kError, std::string(file_), open_line, open_col,
                                "string opened here is never closed"});
    return false;
  }
  bool read_string(std::string& out, const char* what) {
    skip_ws();
    if (peek() != '"') return fail(std::string("expected ") + what + " (a quoted string)");
    const int line = line_;
    if (!read_string_raw(out)) return false;
    if (!is_valid_utf8(out)) {
      out = cp1252_to_utf8(out);
      deviation(line, std::string(what) + " is not UTF-8; read as cp1252");
    }
    return true;
  }
  /// ';' ending a statement; tolerated when missing (a deviation).
  bool end_statement(const char* statement) {
    skip_ws();
    if (peek() == ';') {
      advance();
      return true;
    }
    if (eof() || is_word_char(peek())) {
      deviation(statement_line_, std::string(statement) + " without ';'");
      return true;
    }
    return fail(std::string("expected ';' to end ") + statement);
  }

  // ---------------------------------------------------------------- statements
  void statement(std::string_view kw) {
    if (kw != "SG_") current_message_ = kNone;
    if (kw == "VERSION") {
      read_string(db_.version, "version string");
    } else if (kw == "NS_") {
      parse_ns();
    } else if (kw == "BS_") {
      skip_line();
    } else if (kw == "BU_") {
      parse_bu();
    } else if (kw == "BO_") {
      parse_bo();
    } else if (kw == "SG_") {
      parse_sg();
    } else if (kw == "CM_") {
      parse_cm();
    } else if (kw == "VAL_") {
      parse_val();
    } else if (kw == "VAL_TABLE_") {
      parse_val_table();
    } else if (kw == "BA_DEF_") {
      parse_ba_def();
    } else if (kw == "BA_DEF_DEF_") {
      parse_ba_def_def();
    } else if (kw == "BA_") {
      parse_ba();
    } else if (kw == "SIG_VALTYPE_") {
      parse_sig_valtype();
    } else if (kw == "SG_MUL_VAL_") {
      parse_sg_mul_val();
    } else if (kw == "EV_" || kw == "ENVVAR_DATA_" || kw == "SGTYPE_" || kw == "SGTYPE_VAL_" ||
               kw == "SIG_GROUP_" || kw == "SIG_TYPE_REF_" || kw == "BO_TX_BU_" ||
               kw == "CAT_DEF_" || kw == "CAT_" || kw == "FILTER" || kw == "BU_SG_REL_" ||
               kw == "BU_EV_REL_" || kw == "BU_BO_REL_" || kw == "SIGTYPE_VALTYPE_" ||
               kw == "EV_DATA_" || kw == "BA_DEF_REL_" || kw == "BA_REL_" ||
               kw == "BA_DEF_DEF_REL_" || kw == "BA_DEF_SGTYPE_" || kw == "BA_SGTYPE_" ||
               kw == "NS_DESC_") {
      skip_statement();  // valid statements the decoder has no use for
    } else {
      deviation(statement_line_, "unknown keyword '" + std::string(kw) + "': line skipped");
      skip_line();
    }
  }

  void parse_ns() {
    skip_blanks();
    if (peek() == ':') advance();
    skip_line();
    // The symbol list continues on indented lines; the next statement starts in column 1.
    while (!eof() && (peek() == ' ' || peek() == '\t' || peek() == '\r' || peek() == '\n')) {
      skip_line();
    }
  }

  void parse_bu() {
    if (!expect(':', "after BU_")) return;
    while (!at_line_end()) {
      std::string node;
      if (!read_name(node, "node name", false)) return;
      db_.nodes.push_back(node);
    }
  }

  /// A BO_/CM_/BA_/VAL_ message id as written: bit 31 flags an extended id.
  bool read_message_ref(std::uint32_t& raw_id) {
    std::uint64_t v = 0;
    if (!read_uint(v, "message id")) return false;
    if (v > 0xFFFFFFFFull) return fail("message id above 32 bits");
    raw_id = static_cast<std::uint32_t>(v);
    return true;
  }

  void parse_bo() {
    const int line = statement_line_;
    std::uint32_t raw_id = 0;
    if (!read_message_ref(raw_id)) return;
    Message m;
    m.line = line;
    skip_blanks();
    const bool independent = s_.substr(pos_, kIndependentSignals.size()) == kIndependentSignals;
    if (!read_name(m.name, "message name")) return;
    if (!expect(':', "after the message name")) return;
    std::uint64_t dlc = 0;
    if (!read_uint(dlc, "message length (bytes)")) return;
    if (!at_line_end()) {
      if (!read_name(m.transmitter, "transmitter node", false)) return;
    }
    if (independent) {
      ignored_ids_.insert(raw_id);
      current_message_ = kIgnored;
      return;
    }
    if (dlc > static_cast<std::uint64_t>(kFdMaxLen)) {
      error_at(line, "message " + m.name + " is " + std::to_string(dlc) +
                         " bytes long; CAN FD carries at most 64");
      dlc = kFdMaxLen;
    }
    m.length = static_cast<int>(dlc);
    m.id = raw_id;
    if (raw_id & kDbcExtendedBit) {
      m.extended = true;
      m.id = raw_id & kEffMask;
      if ((raw_id & ~kDbcExtendedBit) > kEffMask) {
        deviation(line, "message " + m.name + ": id " + std::to_string(raw_id) +
                            " has bits above the 29-bit identifier; masked to 0x" + hex(m.id));
      }
    } else if (raw_id > kSffMask) {
      m.id = raw_id & kEffMask;
      m.extended = true;
      if (raw_id > kEffMask) {
        m.extended = m.id > kSffMask;
        deviation(line, "message " + m.name + ": id " + std::to_string(raw_id) + " (0x" +
                            hex(raw_id) + ") sets bits 29-30 without bit 31; read as " +
                            (m.extended ? "extended" : "standard") + " id 0x" + hex(m.id));
      } else {
        deviation(line, "message " + m.name + ": id " + std::to_string(raw_id) + " (0x" +
                            hex(raw_id) + ") is above 0x7FF without bit 31; read as extended id");
      }
    }
    if (m.length > kClassicMaxLen && !is_valid_fd_length(m.length)) {
      deviation(line, "message " + m.name + ": length " + std::to_string(m.length) +
                          " is not a CAN FD length");
    }
    const auto key = (static_cast<std::uint64_t>(m.extended) << 32) | m.id;
    if (const auto it = by_key_.find(key); it != by_key_.end()) {
      error_at(line, "message " + m.name + " has the same id as " +
                         db_.messages[static_cast<std::size_t>(it->second)].name + " (line " +
                         std::to_string(db_.messages[static_cast<std::size_t>(it->second)].line) +
                         ")");
      current_message_ = kIgnored;
      return;
    }
    const int index = static_cast<int>(db_.messages.size());
    by_key_[key] = index;
    by_raw_id_[raw_id] = index;
    db_.messages.push_back(std::move(m));
    current_message_ = index;
  }

  // NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
  void parse_sg() {
    const int line = statement_line_;
    if (current_message_ == kNone) {
      fail("SG_ outside a BO_ message");
      return;
    }
    Signal sg;
    sg.line = line;
    if (!read_name(sg.name, "signal name")) return;
    skip_blanks();
    if (peek() != ':') {
      const std::string_view mux = read_word();
      if (mux == "M") {
        sg.is_multiplexor = true;
      } else if (mux.size() >= 2 && mux[0] == 'm' && is_digit(mux[1])) {
        std::size_t e = 1;
        while (e < mux.size() && is_digit(mux[e])) ++e;
        std::uint64_t v = 0;
        std::from_chars(mux.data() + 1, mux.data() + e, v);
        sg.mux_value = v;
        if (e < mux.size()) {
          if (mux.substr(e) != "M") {
            pos_ -= mux.size();
            fail("expected multiplexer indicator (M, mNN or mNNM) or ':'");
            return;
          }
          sg.is_multiplexor = true;
        }
      } else {
        pos_ -= mux.size();
        fail("expected multiplexer indicator (M, mNN or mNNM) or ':'");
        return;
      }
    }
    if (!expect(':', "after the signal name")) return;
    std::uint64_t start = 0, length = 0;
    if (!read_uint(start, "start bit")) return;
    if (!expect('|', "between start bit and length")) return;
    if (!read_uint(length, "signal length")) return;
    if (!expect('@', "before the byte order")) return;
    if (peek() == '0') {
      sg.byte_order = ByteOrder::kMotorola;
    } else if (peek() == '1') {
      sg.byte_order = ByteOrder::kIntel;
    } else {
      fail("expected byte order 0 (Motorola) or 1 (Intel) after '@'");
      return;
    }
    advance();
    if (peek() == '+' || peek() == '-') {
      sg.is_signed = peek() == '-';
      advance();
    } else {
      fail("expected sign '+' or '-' after the byte order");
      return;
    }
    if (!expect('(', "before factor")) return;
    if (!read_double(sg.factor, "factor")) return;
    if (!expect(',', "between factor and offset")) return;
    if (!read_double(sg.offset, "offset")) return;
    if (!expect(')', "after offset")) return;
    if (!expect('[', "before minimum")) return;
    if (!read_double(sg.minimum, "minimum")) return;
    if (!expect('|', "between minimum and maximum")) return;
    if (!read_double(sg.maximum, "maximum")) return;
    if (!expect(']', "after maximum")) return;
    sg.has_range = !(sg.minimum == 0.0 && sg.maximum == 0.0);
    if (!read_string(sg.unit, "unit")) return;
    while (!at_line_end()) {
      if (peek() == ',') {
        advance();
        continue;
      }
      std::string r;
      if (!read_name(r, "receiver node", false)) return;
      sg.receivers.push_back(std::move(r));
    }
    if (start > 4096 || length > 4096) {
      error_at(line, "signal " + sg.name + ": start bit or length out of range");
      return;
    }
    sg.start_bit = static_cast<int>(start);
    sg.length = static_cast<int>(length);
    if (current_message_ == kIgnored) return;
    db_.messages[static_cast<std::size_t>(current_message_)].signals.push_back(std::move(sg));
  }

  /// Message index for a reference by raw id; -1 (after a warning) when unknown, -2 when the
  /// id belongs to a skipped message.
  int message_for(std::uint32_t raw_id, const char* statement) {
    if (const auto it = by_raw_id_.find(raw_id); it != by_raw_id_.end()) return it->second;
    if (ignored_ids_.count(raw_id) != 0) return -2;
    deviation(statement_line_,
              std::string(statement) + " refers to unknown message id " + std::to_string(raw_id));
    return -1;
  }
  Signal* signal_for(int msg, const std::string& name, const char* statement) {
    if (msg < 0) return nullptr;
    Message& m = db_.messages[static_cast<std::size_t>(msg)];
    const int i = m.find_signal(name);
    if (i < 0) {
      deviation(statement_line_, std::string(statement) + " refers to unknown signal " + name +
                                     " of message " + m.name);
      return nullptr;
    }
    return &m.signals[static_cast<std::size_t>(i)];
  }

  void parse_cm() {
    skip_ws();
    std::string text;
    if (peek() == '"') {
      if (!read_string(text, "comment")) return;
      db_.comment = text;
      end_statement("CM_");
      return;
    }
    if (!is_word_char(peek())) {
      fail("expected BU_, BO_, SG_, EV_ or a quoted comment after CM_");
      return;
    }
    const std::size_t word_pos = pos_;
    const std::string kw(read_word());
    if (kw == "BU_" || kw == "EV_") {
      std::string name;
      if (!read_name(name, kw == "BU_" ? "node name" : "environment variable name")) return;
      if (!read_string(text, "comment")) return;
    } else if (kw == "BO_" || kw == "SG_" || is_digit(kw[0])) {
      bool is_signal = kw == "SG_";
      if (is_digit(kw[0])) {
        pos_ = word_pos;  // the id itself: the object keyword is missing
      }
      std::uint32_t raw_id = 0;
      if (!read_message_ref(raw_id)) return;
      std::string signal_name;
      if (is_digit(kw[0])) {
        skip_ws();
        is_signal = peek() != '"';
        deviation(statement_line_, std::string("CM_ without object keyword: read as CM_ ") +
                                       (is_signal ? "SG_" : "BO_"));
      }
      if (is_signal && !read_name(signal_name, "signal name")) return;
      if (!read_string(text, "comment")) return;
      const int msg = message_for(raw_id, "CM_");
      if (is_signal) {
        if (Signal* sg = signal_for(msg, signal_name, "CM_")) sg->comment = text;
      } else if (msg >= 0) {
        db_.messages[static_cast<std::size_t>(msg)].comment = text;
      }
    } else {
      pos_ = word_pos;
      fail("expected BU_, BO_, SG_, EV_ or a quoted comment after CM_");
      return;
    }
    end_statement("CM_");
  }

  /// `value "text"` pairs up to ';' (VAL_, VAL_TABLE_).
  bool read_value_pairs(std::vector<ValueDescription>& out, const char* statement) {
    while (true) {
      skip_ws();
      const char c = peek();
      if (c == ';') {
        advance();
        return true;
      }
      if (eof() || (is_word_char(c) && !is_digit(c))) {
        deviation(statement_line_, std::string(statement) + " without ';'");
        return true;
      }
      double v = 0.0;
      if (!read_double(v, "raw value or ';'")) return false;
      ValueDescription d;
      d.value = static_cast<std::int64_t>(v);
      if (static_cast<double>(d.value) != v) {
        deviation(statement_line_, std::string(statement) + " value " + std::to_string(v) +
                                       " is not an integer; truncated");
      }
      if (!read_string(d.text, "value description")) return false;
      out.push_back(std::move(d));
    }
  }

  void parse_val() {
    skip_ws();
    if (is_digit(peek())) {
      std::uint32_t raw_id = 0;
      if (!read_message_ref(raw_id)) return;
      std::string signal_name;
      if (!read_name(signal_name, "signal name")) return;
      std::vector<ValueDescription> values;
      if (!read_value_pairs(values, "VAL_")) return;
      if (Signal* sg = signal_for(message_for(raw_id, "VAL_"), signal_name, "VAL_")) {
        sg->values = std::move(values);
      }
      return;
    }
    std::string env;
    if (!read_name(env, "message id or environment variable")) return;
    std::vector<ValueDescription> ignored;
    read_value_pairs(ignored, "VAL_");
  }

  void parse_val_table() {
    ValueTable t;
    if (!read_name(t.name, "value table name")) return;
    if (!read_value_pairs(t.values, "VAL_TABLE_")) return;
    db_.value_tables.push_back(std::move(t));
  }

  /// An attribute value: a quoted string or a number, kept as text.
  bool read_attribute_value(std::string& out) {
    skip_ws();
    if (peek() == '"') return read_string(out, "attribute value");
    double v = 0.0;
    const std::size_t b = pos_;
    if (!read_double(v, "attribute value")) return false;
    out = std::string(s_.substr(b, pos_ - b));
    while (!out.empty() && (out.front() == ' ' || out.front() == '\t' || out.front() == '\n' ||
                            out.front() == '\r')) {
      out.erase(out.begin());
    }
    return true;
  }

  void parse_ba_def() {
    AttributeDefinition def;
    skip_ws();
    if (peek() != '"') {
      const std::size_t p = pos_;
      def.object = std::string(read_word());
      if (def.object != "BU_" && def.object != "BO_" && def.object != "SG_" &&
          def.object != "EV_") {
        pos_ = p;
        fail("expected BU_, BO_, SG_, EV_ or the attribute name after BA_DEF_");
        return;
      }
    }
    if (!read_string(def.name, "attribute name")) return;
    if (!read_name(def.type, "attribute type (INT, HEX, FLOAT, STRING, ENUM)")) return;
    if (def.type == "INT" || def.type == "HEX" || def.type == "FLOAT") {
      double lo = 0.0, hi = 0.0;
      if (!read_double(lo, "attribute minimum")) return;
      if (!read_double(hi, "attribute maximum")) return;
    } else if (def.type == "ENUM") {
      while (true) {
        skip_ws();
        if (peek() != '"') break;
        std::string v;
        if (!read_string(v, "enum value")) return;
        def.enum_values.push_back(std::move(v));
        skip_ws();
        if (peek() != ',') break;
        advance();
      }
    } else if (def.type != "STRING") {
      fail("expected attribute type INT, HEX, FLOAT, STRING or ENUM");
      return;
    }
    if (!end_statement("BA_DEF_")) return;
    db_.attributes.push_back(std::move(def));
  }

  AttributeDefinition* attribute(const std::string& name) {
    for (auto& a : db_.attributes) {
      if (a.name == name) return &a;
    }
    return nullptr;
  }

  void parse_ba_def_def() {
    std::string name, value;
    if (!read_string(name, "attribute name")) return;
    if (!read_attribute_value(value)) return;
    if (!end_statement("BA_DEF_DEF_")) return;
    if (AttributeDefinition* def = attribute(name)) {
      def->default_value = value;
    } else {
      deviation(statement_line_, "BA_DEF_DEF_ for undefined attribute \"" + name + "\"");
    }
  }

  void parse_ba() {
    std::string name, value;
    if (!read_string(name, "attribute name")) return;
    skip_ws();
    int msg = -1;
    if (is_word_char(peek()) && !is_digit(peek())) {
      const std::size_t p = pos_;
      const std::string object(read_word());
      std::string other;
      if (object == "BU_" || object == "EV_") {
        if (!read_name(other, "object name")) return;
      } else if (object == "BO_" || object == "SG_") {
        std::uint32_t raw_id = 0;
        if (!read_message_ref(raw_id)) return;
        if (object == "SG_" && !read_name(other, "signal name")) return;
        if (object == "BO_") msg = message_for(raw_id, "BA_");
      } else {
        pos_ = p;
        fail("expected BU_, BO_, SG_, EV_ or a value after the attribute name");
        return;
      }
    }
    if (!read_attribute_value(value)) return;
    if (!end_statement("BA_")) return;
    if (msg >= 0) apply_message_attribute(db_.messages[static_cast<std::size_t>(msg)], name, value);
  }

  void apply_message_attribute(Message& m, const std::string& name, const std::string& value) {
    if (name == "GenMsgCycleTime") {
      double v = 0.0;
      const char* b = value.data();
      if (std::from_chars(b, b + value.size(), v).ec == std::errc() && v >= 0.0 && v < 1e9) {
        m.cycle_time_ms = static_cast<int>(v);
        explicit_cycle_.insert(&m - db_.messages.data());
      } else {
        deviation(statement_line_, "GenMsgCycleTime of " + m.name + " is not a number");
      }
    } else if (name == "VFrameFormat") {
      m.fd = frame_format_is_fd(value);
      explicit_format_.insert(&m - db_.messages.data());
    }
  }

  bool frame_format_is_fd(const std::string& value) {
    const AttributeDefinition* def = attribute("VFrameFormat");
    std::string text = value;
    long index = -1;
    const char* b = value.data();
    if (std::from_chars(b, b + value.size(), index).ec == std::errc() && def != nullptr &&
        index >= 0 && static_cast<std::size_t>(index) < def->enum_values.size()) {
      text = def->enum_values[static_cast<std::size_t>(index)];
    }
    return text.find("FD") != std::string::npos;
  }

  void parse_sig_valtype() {
    std::uint32_t raw_id = 0;
    if (!read_message_ref(raw_id)) return;
    std::string signal_name;
    if (!read_name(signal_name, "signal name")) return;
    if (!expect(':', "before the value type")) return;
    std::uint64_t type = 0;
    if (!read_uint(type, "value type 0, 1 (float32) or 2 (float64)")) return;
    if (!end_statement("SIG_VALTYPE_")) return;
    if (type > 2) {
      error_at(statement_line_,
               "SIG_VALTYPE_ " + signal_name + ": unknown value type " + std::to_string(type));
      return;
    }
    if (Signal* sg = signal_for(message_for(raw_id, "SIG_VALTYPE_"), signal_name, "SIG_VALTYPE_")) {
      sg->value_type = type == 1   ? ValueType::kFloat32
                       : type == 2 ? ValueType::kFloat64
                                   : ValueType::kInteger;
    }
  }

  void parse_sg_mul_val() {
    MulValEntry e;
    e.line = statement_line_;
    if (!read_message_ref(e.raw_id)) return;
    if (!read_name(e.signal, "signal name")) return;
    if (!read_name(e.switch_name, "multiplexor switch name")) return;
    while (true) {
      MuxRange r;
      if (!read_uint(r.lo, "range start")) return;
      if (!expect('-', "in the switch value range")) return;
      if (!read_uint(r.hi, "range end")) return;
      if (r.hi < r.lo) {
        error_at(e.line, "SG_MUL_VAL_ " + e.signal + ": empty range");
        return;
      }
      e.ranges.push_back(r);
      skip_ws();
      if (peek() != ',') break;
      advance();
    }
    if (!end_statement("SG_MUL_VAL_")) return;
    mul_vals_.push_back(std::move(e));
  }

  // ---------------------------------------------------------------- finishing pass
  void finish() {
    // Attribute defaults.
    const AttributeDefinition* cycle = attribute("GenMsgCycleTime");
    const AttributeDefinition* format = attribute("VFrameFormat");
    for (std::size_t i = 0; i < db_.messages.size(); ++i) {
      Message& m = db_.messages[i];
      if (cycle && !cycle->default_value.empty() &&
          explicit_cycle_.count(static_cast<long>(i)) == 0) {
        double v = 0.0;
        const char* b = cycle->default_value.data();
        if (std::from_chars(b, b + cycle->default_value.size(), v).ec == std::errc() && v >= 0 &&
            v < 1e9) {
          m.cycle_time_ms = static_cast<int>(v);
        }
      }
      if (format && !format->default_value.empty() &&
          explicit_format_.count(static_cast<long>(i)) == 0) {
        m.fd = frame_format_is_fd(format->default_value);
      }
      if (m.length > kClassicMaxLen) m.fd = true;  // only CAN FD carries more than 8 bytes
    }
    // Signals the tables cannot hold are reported and left out, so that the rest of the file
    // stays usable; the result is not ok().
    for (Message& m : db_.messages) check_layout(m);
    // Extended multiplexing (by name, so after the layout pass removed signals).
    for (const MulValEntry& e : mul_vals_) {
      const int msg = message_for(e.raw_id, "SG_MUL_VAL_");
      Signal* sg = signal_for(msg, e.signal, "SG_MUL_VAL_");
      if (sg == nullptr) continue;
      Message& m = db_.messages[static_cast<std::size_t>(msg)];
      const int sw = m.find_signal(e.switch_name);
      if (sw < 0 || !m.signals[static_cast<std::size_t>(sw)].is_multiplexor) {
        error_at(e.line, "SG_MUL_VAL_ " + e.signal + ": " + e.switch_name +
                             " is not a multiplexor of message " + m.name);
        sg->mux_parent = kMuxBroken;
        continue;
      }
      sg->mux_parent = sw;
      sg->mux_ranges = e.ranges;
    }
    for (Message& m : db_.messages) resolve_mux(m);
  }

  static constexpr int kMuxBroken = -100;

  void check_layout(Message& m) {
    const int payload_bits = 8 * m.length;
    std::unordered_set<std::string_view> names;
    std::vector<bool> drop(m.signals.size(), false);
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      const Signal& sg = m.signals[i];
      const std::string who = "signal " + sg.name + " of message " + m.name;
      if (!names.insert(sg.name).second) {
        error_at(sg.line, who + ": name used twice; the second is left out");
        drop[i] = true;
        continue;
      }
      if (sg.length < 1 || sg.length > 64) {
        error_at(sg.line, who + ": length " + std::to_string(sg.length) + " is not 1..64 bits");
        drop[i] = true;
        continue;
      }
      if ((sg.value_type == ValueType::kFloat32 && sg.length != 32) ||
          (sg.value_type == ValueType::kFloat64 && sg.length != 64)) {
        error_at(sg.line, who + ": SIG_VALTYPE_ float needs a length of " +
                              (sg.value_type == ValueType::kFloat32 ? "32" : "64") + " bits");
        drop[i] = true;
        continue;
      }
      int last = 0;  // last bit in the layout's own linear numbering
      if (sg.byte_order == ByteOrder::kIntel) {
        last = sg.start_bit + sg.length - 1;
      } else {
        last = (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8) + sg.length - 1;
      }
      if (last >= payload_bits) {
        error_at(sg.line, who + ": bits " + std::to_string(sg.start_bit) + "|" +
                              std::to_string(sg.length) + "@" +
                              (sg.byte_order == ByteOrder::kIntel ? "1" : "0") +
                              " do not fit in the " + std::to_string(m.length) +
                              "-byte payload; signal left out");
        drop[i] = true;
      }
    }
    std::vector<Signal> kept;
    kept.reserve(m.signals.size());
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      if (!drop[i]) kept.push_back(std::move(m.signals[i]));
    }
    m.signals = std::move(kept);
  }

  void resolve_mux(Message& m) {
    int roots = 0, root = -1;
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      const Signal& sg = m.signals[i];
      if (sg.is_multiplexor && !sg.mux_value) {
        ++roots;
        root = static_cast<int>(i);
      }
    }
    std::vector<bool> drop(m.signals.size(), false);
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      Signal& sg = m.signals[i];
      if (sg.mux_parent == kMuxBroken) {
        drop[i] = true;
        continue;
      }
      if (sg.mux_value && sg.mux_parent < 0) {
        if (roots == 1 && root != static_cast<int>(i)) {
          sg.mux_parent = root;
          sg.mux_ranges = {MuxRange{*sg.mux_value, *sg.mux_value}};
        } else {
          error_at(sg.line, "signal " + sg.name + " of message " + m.name + " is multiplexed (m" +
                                std::to_string(*sg.mux_value) + ") but " +
                                (roots == 0 ? "the message has no multiplexor (M)"
                                            : "the message has several multiplexors and no "
                                              "SG_MUL_VAL_ names this signal's") +
                                "; signal left out");
          drop[i] = true;
        }
      }
    }
    // A chain that loops, or that runs through a dropped switch, drops the signal.
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::size_t i = 0; i < m.signals.size(); ++i) {
        if (drop[i]) continue;
        int p = m.signals[i].mux_parent;
        std::size_t steps = 0;
        bool bad = false;
        while (p >= 0) {
          if (drop[static_cast<std::size_t>(p)] || ++steps > m.signals.size()) {
            bad = true;
            break;
          }
          p = m.signals[static_cast<std::size_t>(p)].mux_parent;
        }
        if (bad) {
          error_at(m.signals[i].line, "signal " + m.signals[i].name + " of message " + m.name +
                                          ": its multiplexor chain is broken or loops; "
                                          "signal left out");
          drop[i] = true;
          changed = true;
        }
      }
    }
    std::vector<int> new_index(m.signals.size(), -1);
    std::vector<Signal> kept;
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      if (drop[i]) continue;
      new_index[i] = static_cast<int>(kept.size());
      kept.push_back(std::move(m.signals[i]));
    }
    for (Signal& sg : kept) {
      if (sg.mux_parent >= 0) sg.mux_parent = new_index[static_cast<std::size_t>(sg.mux_parent)];
    }
    m.signals = std::move(kept);
    check_overlaps(m);
  }

  static std::bitset<8 * kFdMaxLen> bits_of(const Signal& sg) {
    std::bitset<8 * kFdMaxLen> b;
    int p = sg.byte_order == ByteOrder::kIntel ? sg.start_bit
                                               : (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8);
    for (int i = 0; i < sg.length; ++i, ++p) {
      // Both layouts as positions in their own linear order; map Motorola back to bit numbers.
      const int bit = sg.byte_order == ByteOrder::kIntel ? p : (p / 8) * 8 + (7 - p % 8);
      if (bit >= 0 && bit < 8 * kFdMaxLen) b.set(static_cast<std::size_t>(bit));
    }
    return b;
  }

  /// (switch, ranges selecting the next link) from a signal up to the root of its mux tree.
  static std::vector<std::pair<int, const std::vector<MuxRange>*>> mux_chain(const Message& m,
                                                                             std::size_t i) {
    std::vector<std::pair<int, const std::vector<MuxRange>*>> chain;
    const Signal* s = &m.signals[i];
    while (s->mux_parent >= 0 && chain.size() <= m.signals.size()) {
      chain.emplace_back(s->mux_parent, &s->mux_ranges);
      s = &m.signals[static_cast<std::size_t>(s->mux_parent)];
    }
    return chain;
  }

  /// False when some switch both depend on selects them with disjoint values.
  static bool can_coexist(const Message& m, std::size_t i, std::size_t j) {
    for (const auto& [p, ra] : mux_chain(m, i)) {
      for (const auto& [q, rb] : mux_chain(m, j)) {
        if (p != q) continue;
        bool meet = false;
        for (const MuxRange& x : *ra) {
          for (const MuxRange& y : *rb) meet = meet || (x.lo <= y.hi && y.lo <= x.hi);
        }
        if (!meet) return false;
      }
    }
    return true;
  }

  /// Signals that can be present together and share bits: loaded as written, reported.
  void check_overlaps(const Message& m) {
    std::vector<std::bitset<8 * kFdMaxLen>> bits;
    bits.reserve(m.signals.size());
    for (const Signal& sg : m.signals) bits.push_back(bits_of(sg));
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if ((bits[i] & bits[j]).any() && can_coexist(m, i, j)) {
          deviation(m.signals[i].line, "signal " + m.signals[i].name + " of message " + m.name +
                                           " overlaps signal " + m.signals[j].name);
          break;
        }
      }
    }
  }

  static std::string hex(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%X", v);
    return buf;
  }

  static constexpr int kNone = -1;
  static constexpr int kIgnored = -2;

  std::string_view s_;
  std::string_view file_;
  DbcParseOptions options_;
  DbcParseResult& out_;
  Database& db_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
  int statement_line_ = 1;
  bool failed_ = false;
  int current_message_ = kNone;
  std::unordered_map<std::uint64_t, int> by_key_;     // (extended << 32 | id) -> message
  std::unordered_map<std::uint32_t, int> by_raw_id_;  // id as written -> message
  std::unordered_set<std::uint32_t> ignored_ids_;     // VECTOR__INDEPENDENT_SIG_MSG
  std::unordered_set<long> explicit_cycle_, explicit_format_;
  std::vector<MulValEntry> mul_vals_;
};

}  // namespace

DbcParseResult parse_dbc(std::string_view text, std::string_view file,
                         const DbcParseOptions& options) {
  DbcParseResult result;
  Parser(text, file, options, result).run();
  return result;
}

DbcParseResult load_dbc_file(const std::string& path, const DbcParseOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    DbcParseResult result;
    result.diagnostics.push_back(
        {Severity::kError, path, 0, 0, std::string("cannot open: ") + std::strerror(errno)});
    return result;
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_dbc(ss.str(), path, options);
}

}  // namespace vmass::can
