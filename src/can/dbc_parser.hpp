// The DBC parser's internals (src/can only): the Parser class, whose members live in
//   dbc_lexer.cpp       the cursor, diagnostics and tokens (names, numbers, strings)
//   dbc_statements.cpp  one parser per statement (BO_, SG_, CM_, BA_DEF_, VAL_, ...)
//   dbc_checks.cpp      the pass after the text: layouts, multiplexing, overlaps, defaults
//   dbc_parser.cpp      the run, parse_dbc and load_dbc_file, the database's look-ups
// and the text helpers they share. See include/vmass/can/dbc.hpp for what is accepted.
#pragma once

#include <bitset>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/dbc.hpp"

namespace vmass::can::dbc_detail {

constexpr std::string_view kIndependentSignals = "VECTOR__INDEPENDENT_SIG_MSG";

inline bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
/// True when s is well-formed UTF-8.
bool is_valid_utf8(std::string_view s);
/// Windows-1252 text (what many DBC tools write) as UTF-8.
std::string cp1252_to_utf8(std::string_view s);

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
  void run();

  static constexpr int kMaxErrors = 100;  ///< then the rest of the file is not read
  static constexpr std::size_t kMaxNameBytes = 256;

 private:
  /// False (one error) for binary data or an empty file.
  bool is_text();
  /// After a failed statement: on to the next line that starts with a keyword.
  void recover();
  void skip_rest_of_line();
  static bool is_keyword(std::string_view word);

  // ---------------------------------------------------------------- cursor
  bool eof() const { return pos_ >= s_.size(); }
  char peek() const { return eof() ? '\0' : s_[pos_]; }
  int column() const { return static_cast<int>(pos_ - line_start_) + 1; }
  void advance();
  /// Spaces, tabs and carriage returns (CRLF files), not newlines.
  void skip_blanks();
  void skip_ws();
  bool at_line_end();
  std::string_view read_word();
  /// Skips to the end of the line; a quoted string may span lines.
  void skip_line();
  /// Skips past the next ';' outside quoted strings.
  void skip_statement();

  // ---------------------------------------------------------------- diagnostics
  bool fail(const std::string& what);
  void error_at(int line, const std::string& what);
  /// A departure from the format that we load as meant: a warning, or an error in strict mode.
  void deviation(int line, const std::string& what);
  /// Worth knowing, but within the format: a warning even in strict mode.
  void warning(int line, const std::string& what);

  // ---------------------------------------------------------------- tokens
  bool expect(char c, const char* context);
  bool read_name(std::string& out, const char* what, bool newline_ok = true);
  bool read_uint(std::uint64_t& v, const char* what);
  /// Scans a decimal number ([+-]digits[.digits][e[+-]digits]) and converts it locale-free.
  bool read_double(double& v, const char* what);
  /// A quoted string; \" and \\ are escapes; newlines inside are kept. No encoding check.
  bool read_string_raw(std::string& out);
  bool read_string(std::string& out, const char* what);
  /// ';' ending a statement; tolerated when missing (a deviation).
  bool end_statement(const char* statement);

  // ---------------------------------------------------------------- statements
  void statement(std::string_view kw);
  void parse_ns();
  void parse_bu();

  /// A BO_/CM_/BA_/VAL_ message id as written: bit 31 flags an extended id.
  bool read_message_ref(std::uint32_t& raw_id);
  void parse_bo();
  void parse_sg();
  /// After a signal name: M, mNN or mNNM (multiplexing). False after an error.
  bool read_mux_indicator(Signal& sg);
  /// @0+ / @1- ...: byte order and sign. False after an error.
  bool read_byte_order_and_sign(Signal& sg);
  /// (factor,offset) [minimum|maximum]. False after an error.
  bool read_scaling(Signal& sg);

  /// Message index for a reference by raw id; -1 (after a warning) when unknown, -2 when the
  /// id belongs to a skipped message.
  int message_for(std::uint32_t raw_id, const char* statement);
  Signal* signal_for(int msg, const std::string& name, const char* statement);
  void parse_cm();

  /// `value "text"` pairs up to ';' (VAL_, VAL_TABLE_).
  bool read_value_pairs(std::vector<ValueDescription>& out, const char* statement);
  void parse_val();
  void parse_val_table();

  /// An attribute value: a quoted string or a number, kept as text.
  bool read_attribute_value(std::string& out);
  void parse_ba_def();
  AttributeDefinition* attribute(const std::string& name);
  void parse_ba_def_def();
  void parse_ba();
  void apply_message_attribute(Message& m, const std::string& name, const std::string& value);
  bool frame_format_is_fd(const std::string& value);
  void parse_sig_valtype();
  void parse_sg_mul_val();

  // ---------------------------------------------------------------- finishing pass
  void finish();
  static constexpr int kMuxBroken = -100;
  void check_layout(Message& m);
  /// A [min|max] the signal's bits cannot carry (e.g. [0|65535] on a signed 16-bit yaw rate):
  /// a warning; vmass does not discard values by DBC ranges.
  void check_declared_range(const Message& m, const Signal& sg);
  /// Multiplexed signals whose values their switch can never hold: a warning.
  void check_mux_values(const Message& m);
  void resolve_mux(Message& m);
  static std::bitset<8 * kFdMaxLen> bits_of(const Signal& sg);

  /// (switch, ranges selecting the next link) from a signal up to the root of its mux tree.
  using MuxChain = std::vector<std::pair<int, const std::vector<MuxRange>*>>;
  static MuxChain mux_chain(const Message& m, std::size_t i);

  /// False when some switch both signals depend on selects them with disjoint values. Adds the
  /// range comparisons it made to *work.
  static bool can_coexist(const MuxChain& a, const MuxChain& b, long* work);

  /// Signals that can be present together and share bits: loaded as written, reported.
  void check_overlaps(const Message& m);
  static std::string hex(std::uint32_t v);
  static constexpr int kNone = -1;
  static constexpr int kIgnored = -2;
  /// What a message may hold: far beyond any real file (the largest of ours has 64 signals), and
  /// small enough that every check of a message stays cheap (the overlap check is pairwise).
  static constexpr std::size_t kMaxSignalsPerMessage = 4096;
  static constexpr std::size_t kMaxMuxRanges = 1024;  ///< per SG_MUL_VAL_ statement
  void index_signals(std::size_t msg);

  std::string_view s_;
  std::string_view file_;
  DbcParseOptions options_;
  DbcParseResult& out_;
  Database& db_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
  int statement_line_ = 1;
  bool failed_ = false;   ///< the current statement failed (recover() skips the rest of it)
  bool stopped_ = false;  ///< too many errors: the rest of the file is not read
  int errors_recovered_ = 0;
  int current_message_ = kNone;
  std::unordered_map<std::uint64_t, int> by_key_;     // (extended << 32 | id) -> message
  std::unordered_map<std::uint32_t, int> by_raw_id_;  // id as written -> message
  std::unordered_map<std::string, int> by_name_;      // message name -> first message
  /// Per message: signal name -> its first signal (statements name signals: a linear search
  /// per statement made a message of 45,000 signals quadratic). Rebuilt after check_layout.
  std::vector<std::unordered_map<std::string, int>> signal_index_;
  std::unordered_set<std::size_t> signals_left_out_;  ///< messages past kMaxSignalsPerMessage
  std::unordered_set<std::uint32_t> ignored_ids_;     // VECTOR__INDEPENDENT_SIG_MSG
  std::unordered_set<long> explicit_cycle_, explicit_format_;
  std::vector<MulValEntry> mul_vals_;
};

}  // namespace vmass::can::dbc_detail
