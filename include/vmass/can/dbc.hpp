// DBC database: the parsed contents of a Vector DBC file, and the parser that reads it.
//
// What a signal means: the raw value is `length` bits taken from the payload, starting at
// `start_bit`. Intel (`@1`): the start bit is the least significant bit, bit b is bit b%8 of byte
// b/8. Motorola (`@0`): the start bit is the most significant bit and the walk to the next less
// significant bit is `b % 8 == 0 ? b + 15 : b - 1`. A signed (`-`) raw value is sign-extended at
// its length (or reinterpreted as IEEE float32/float64 for SIG_VALTYPE_ 1/2), then
//     physical = raw * factor + offset.
// Multiplexing: a signal with `mux_parent` set is present only when that multiplexor switch is
// present and its raw value lies in one of `mux_ranges` (from `mNN` or SG_MUL_VAL_).
//
// The parser is hand-written (no regex) and tolerant by default: deviations found in real files
// (VAL_ without `;`, CM_ without object keyword, ids above 0x7FF without bit 31, names starting
// with a digit, cp1252 text, ...) are loaded as meant and reported as warnings with file:line;
// `DbcParseOptions::strict` turns them into errors. A malformed statement is one error naming
// file, line, column and what was expected, and the parse goes on at the next line that starts
// a statement (every error is reported; after 100 the rest of the file is not read). Binary data
// and empty files are one error. Numbers are parsed locale-free.
//
// Thread-safety: parse_dbc/load_dbc_file are reentrant; a Database is a plain value.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vmass::can {

enum class ByteOrder : std::uint8_t { kIntel, kMotorola };
enum class ValueType : std::uint8_t { kInteger, kFloat32, kFloat64 };

/// A raw value range [lo, hi] of a multiplexor switch that selects a signal.
struct MuxRange {
  std::uint64_t lo = 0;
  std::uint64_t hi = 0;
};

struct ValueDescription {
  std::int64_t value = 0;  ///< raw value
  std::string text;
};

struct Signal {
  std::string name;
  int start_bit = 0;  ///< as written in the DBC (Intel: LSB, Motorola: MSB)
  int length = 0;     ///< bits, 1..64
  ByteOrder byte_order = ByteOrder::kIntel;
  bool is_signed = false;
  ValueType value_type = ValueType::kInteger;
  double factor = 1.0;
  double offset = 0.0;
  double minimum = 0.0;  ///< [min|max]; [0|0] means no range (has_range false)
  double maximum = 0.0;
  bool has_range = false;
  std::string unit;
  std::vector<std::string> receivers;
  std::string comment;
  std::vector<ValueDescription> values;  ///< VAL_ entries, keys are raw values

  bool is_multiplexor = false;             ///< `M` or `mNNM`: other signals switch on this one
  std::optional<std::uint64_t> mux_value;  ///< `mNN` as written
  int mux_parent = -1;               ///< index of the switch signal in the message, -1 if none
  std::vector<MuxRange> mux_ranges;  ///< raw switch values selecting this signal

  int line = 0;  ///< line of the SG_ statement
};

struct Message {
  std::uint32_t id = 0;  ///< 11- or 29-bit identifier, no flag bits
  bool extended = false;
  std::string name;
  int length = 0;  ///< payload bytes (DLC), 0..64
  std::string transmitter;
  std::string comment;
  bool fd = false;        ///< CAN FD: VFrameFormat says so, or longer than 8 bytes
  int cycle_time_ms = 0;  ///< GenMsgCycleTime, 0 if not given
  std::vector<Signal> signals;
  int line = 0;  ///< line of the BO_ statement

  /// Index of the signal named `name`, or -1.
  int find_signal(std::string_view name) const;
};

struct ValueTable {
  std::string name;
  std::vector<ValueDescription> values;
};

/// An attribute definition (BA_DEF_) and its default (BA_DEF_DEF_), kept as text.
struct AttributeDefinition {
  std::string object;  ///< "", "BU_", "BO_", "SG_", "EV_"
  std::string name;
  std::string type;  ///< INT, HEX, FLOAT, STRING, ENUM
  std::vector<std::string> enum_values;
  std::string default_value;
};

struct Database {
  std::string version;
  std::vector<std::string> nodes;
  std::vector<Message> messages;  ///< in file order, VECTOR__INDEPENDENT_SIG_MSG left out
  std::vector<ValueTable> value_tables;
  std::vector<AttributeDefinition> attributes;
  std::string comment;

  /// Index of the message with this identifier, or -1.
  int find_message(std::uint32_t id, bool extended) const;
  /// Index of the message named `name`, or -1.
  int find_message(std::string_view name) const;
};

enum class Severity : std::uint8_t { kWarning, kError };

struct DbcDiagnostic {
  Severity severity = Severity::kError;
  std::string file;
  int line = 0;
  int column = 0;  ///< 1-based byte column, 0 when the whole statement is meant
  std::string message;

  /// "file:line:column: error: message" (column left out when 0, line too: the whole file).
  std::string to_string() const;
};

struct DbcParseOptions {
  bool strict = false;  ///< deviations from the format are errors instead of warnings
};

struct DbcParseResult {
  Database database;
  std::vector<DbcDiagnostic> diagnostics;  ///< warnings and errors in file order
  bool ok() const;                         ///< no diagnostic is an error
  int error_count() const;
  int warning_count() const;
};

/// Parses DBC text. `file` names the source in diagnostics.
DbcParseResult parse_dbc(std::string_view text, std::string_view file,
                         const DbcParseOptions& options = {});

/// Reads and parses a DBC file; a file that cannot be read is one error diagnostic.
DbcParseResult load_dbc_file(const std::string& path, const DbcParseOptions& options = {});

}  // namespace vmass::can
