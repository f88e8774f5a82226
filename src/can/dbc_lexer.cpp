// The DBC lexer: the cursor over the text (line and column), diagnostics, and the tokens
// (names, numbers, quoted strings in UTF-8 or cp1252). See dbc_parser.hpp.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>

#include "dbc_parser.hpp"
#include "vmass/io/excerpt.hpp"

namespace vmass::can::dbc_detail {
namespace {

// cp1252 bytes 0x80..0x9F as Unicode code points (0 where cp1252 leaves the byte undefined).
constexpr std::uint16_t kCp1252High[32] = {
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

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

/// True when s[pos] ends a line: LF, or a CR that is not the first half of CRLF (old Mac files
/// end their lines with CR alone; in a CRLF file the CR is a blank before the LF).
bool is_line_end(std::string_view s, std::size_t pos) {
  return s[pos] == '\n' || (s[pos] == '\r' && (pos + 1 == s.size() || s[pos + 1] != '\n'));
}

/// A blank within a line: space, tab, the CR of a CRLF.
bool is_blank_at(std::string_view s, std::size_t pos) {
  return s[pos] == ' ' || s[pos] == '\t' || (s[pos] == '\r' && !is_line_end(s, pos));
}

}  // namespace

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

void Parser::advance() {
  if (is_line_end(s_, pos_)) {
    ++line_;
    line_start_ = pos_ + 1;
  }
  ++pos_;
}

void Parser::skip_blanks() {
  while (!eof() && is_blank_at(s_, pos_)) ++pos_;
}

void Parser::skip_ws() {
  while (!eof() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' || s_[pos_] == '\n' ||
                    s_[pos_] == '\f' || s_[pos_] == '\v')) {
    advance();
  }
}

bool Parser::at_line_end() {
  skip_blanks();
  return eof() || is_line_end(s_, pos_);
}

std::string_view Parser::read_word() {
  const std::size_t b = pos_;
  while (!eof() && is_word_char(s_[pos_])) ++pos_;
  return s_.substr(b, pos_ - b);
}

void Parser::skip_line() {
  while (!eof() && !is_line_end(s_, pos_)) {
    if (peek() == '"') {
      std::string ignored;
      if (!read_string_raw(ignored)) return;
      continue;
    }
    advance();
  }
  if (!eof()) advance();
}

void Parser::skip_statement() {
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

void Parser::skip_rest_of_line() {
  while (!eof() && !is_line_end(s_, pos_)) ++pos_;
  if (!eof()) advance();
}

bool Parser::is_keyword(std::string_view word) {
  static constexpr std::string_view kKeywords[] = {"VERSION",
                                                   "NS_",
                                                   "BS_",
                                                   "BU_",
                                                   "BO_",
                                                   "SG_",
                                                   "CM_",
                                                   "VAL_",
                                                   "VAL_TABLE_",
                                                   "BA_DEF_",
                                                   "BA_DEF_DEF_",
                                                   "BA_",
                                                   "SIG_VALTYPE_",
                                                   "SG_MUL_VAL_",
                                                   "EV_",
                                                   "ENVVAR_DATA_",
                                                   "SGTYPE_",
                                                   "SGTYPE_VAL_",
                                                   "SIG_GROUP_",
                                                   "SIG_TYPE_REF_",
                                                   "BO_TX_BU_",
                                                   "CAT_DEF_",
                                                   "CAT_",
                                                   "FILTER",
                                                   "BU_SG_REL_",
                                                   "BU_EV_REL_",
                                                   "BU_BO_REL_",
                                                   "SIGTYPE_VALTYPE_",
                                                   "EV_DATA_",
                                                   "BA_DEF_REL_",
                                                   "BA_REL_",
                                                   "BA_DEF_DEF_REL_",
                                                   "BA_DEF_SGTYPE_",
                                                   "BA_SGTYPE_",
                                                   "NS_DESC_"};
  for (std::string_view k : kKeywords) {
    if (word == k) return true;
  }
  return false;
}

bool Parser::fail(const std::string& what) {
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
    found = "'" + io::excerpt(s_.substr(b, e - b)) + "'";
  }
  out_.diagnostics.push_back(
      {Severity::kError, std::string(file_), line_, column(), what + ", found " + found});
  return false;
}

void Parser::error_at(int line, const std::string& what) {
  out_.diagnostics.push_back({Severity::kError, std::string(file_), line, 0, what});
}

void Parser::deviation(int line, const std::string& what) {
  out_.diagnostics.push_back(
      {options_.strict ? Severity::kError : Severity::kWarning, std::string(file_), line, 0, what});
}

void Parser::warning(int line, const std::string& what) {
  out_.diagnostics.push_back({Severity::kWarning, std::string(file_), line, 0, what});
}

bool Parser::expect(char c, const char* context) {
  skip_blanks();
  if (peek() != c) return fail(std::string("expected '") + c + "' " + context);
  advance();
  return true;
}

bool Parser::read_name(std::string& out, const char* what, bool newline_ok) {
  if (newline_ok) {
    skip_ws();
  } else {
    skip_blanks();
  }
  const int line = line_;
  if (!is_word_char(peek())) return fail(std::string("expected ") + what);
  const std::size_t begin = pos_;
  const std::string_view word = read_word();
  if (word.size() > kMaxNameBytes) {
    pos_ = begin;
    return fail(std::string(what) + " longer than " + std::to_string(kMaxNameBytes) +
                " characters");
  }
  out = std::string(word);
  if (is_digit(out[0])) {
    deviation(line, std::string(what) + " '" + out + "' begins with a digit");
  }
  return true;
}

bool Parser::read_uint(std::uint64_t& v, const char* what) {
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

bool Parser::read_double(double& v, const char* what) {
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

bool Parser::read_string_raw(std::string& out) {
  if (peek() != '"') return fail("expected '\"'");
  const int open_line = line_;
  const int open_col = column();
  const std::size_t open_pos = pos_;
  const std::size_t open_line_start = line_start_;
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
    if (c != '\r') {
      out += c;
    } else if (is_line_end(s_, pos_)) {
      out += '\n';  // a CR-only file's line break within a string
    }
    advance();
  }
  failed_ = true;
  out_.diagnostics.push_back({Severity::kError, std::string(file_), open_line, open_col,
                              "string opened here is never closed"});
  // Recovery goes on from the line of the opening quote, not from the end of the file.
  pos_ = open_pos + 1;
  line_ = open_line;
  line_start_ = open_line_start;
  return false;
}

bool Parser::read_string(std::string& out, const char* what) {
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

bool Parser::end_statement(const char* statement) {
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

}  // namespace vmass::can::dbc_detail
