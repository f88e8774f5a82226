// Hand-written DBC parser (see include/vmass/can/dbc.hpp for what it accepts and reports; its
// parts: dbc_parser.hpp).
//
// A cursor walks the text byte by byte, tracking line and column. Each statement starts with a
// keyword; known statements are parsed field by field, statements we do not use are skipped up
// to their ';' (respecting quoted strings), unknown keywords are skipped to the end of the line
// with a warning. After the text, a finishing pass attaches multiplexing, checks every signal
// against its message and applies attribute defaults.
#include <algorithm>

#include "vmass/can/dbc.hpp"
#include "vmass/io/regular_file.hpp"

#include "dbc_parser.hpp"

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
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
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

namespace dbc_detail {

void Parser::run() {
  if (s_.size() >= 3 && s_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 byte order mark
  if (!is_text()) return;
  while (!stopped_) {
    skip_ws();
    if (eof()) break;
    statement_line_ = line_;
    const char c = peek();
    if (!is_word_char(c)) {
      fail("expected a keyword (VERSION, BO_, SG_, CM_, ...)");
    } else {
      statement(read_word());
    }
    if (failed_) recover();
  }
  finish();  // also after errors: what was loaded is checked and stays consistent
  if (db_.messages.empty() && out_.error_count() == 0) {
    deviation(0, "no message (BO_) in the file");
  }
}

bool Parser::is_text() {
  const std::size_t nul = s_.find('\0');
  if (nul != std::string_view::npos) {
    const int line = 1 + static_cast<int>(std::count(s_.begin(), s_.begin() + nul, '\n'));
    error_at(line, "binary data (a NUL byte): not a DBC file");
    return false;
  }
  std::size_t i = pos_;
  while (i < s_.size() && (s_[i] == ' ' || s_[i] == '\t' || s_[i] == '\r' || s_[i] == '\n')) ++i;
  if (i == s_.size()) {
    error_at(0, "empty file: not a DBC file");
    return false;
  }
  return true;
}

void Parser::recover() {
  failed_ = false;
  if (++errors_recovered_ >= kMaxErrors) {
    error_at(line_, "too many errors (" + std::to_string(kMaxErrors) +
                        "); the rest of the file is not read");
    stopped_ = true;
    return;
  }
  // The statement is abandoned: on to the next line that starts with a keyword.
  skip_rest_of_line();
  while (!eof()) {
    const std::size_t line_begin = pos_;
    skip_blanks();
    const std::size_t word_begin = pos_;
    const std::string_view word = read_word();
    pos_ = word_begin;
    if (is_keyword(word)) return;
    pos_ = line_begin;
    skip_rest_of_line();
  }
}

}  // namespace dbc_detail

using dbc_detail::Parser;

DbcParseResult parse_dbc(std::string_view text, std::string_view file,
                         const DbcParseOptions& options) {
  DbcParseResult result;
  Parser(text, file, options, result).run();
  return result;
}

DbcParseResult load_dbc_file(const std::string& path, const DbcParseOptions& options) {
  const io::FileText file = io::read_regular_file(path, io::kMaxDbcBytes, "DBC");
  if (!file.ok()) {
    DbcParseResult result;
    // "path: cannot open|read the DBC: why": the diagnostic adds the path itself.
    result.diagnostics.push_back(
        {Severity::kError, path, 0, 0, file.error.substr(path.size() + 2)});
    return result;
  }
  return parse_dbc(file.text, path, options);
}

}  // namespace vmass::can
