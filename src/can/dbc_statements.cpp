// The DBC statement parsers: one per statement vmass uses (NS_, BU_, BO_, SG_, CM_, VAL_,
// VAL_TABLE_, BA_DEF_, BA_DEF_DEF_, BA_, SIG_VALTYPE_, SG_MUL_VAL_); others are skipped. See
// dbc_parser.hpp.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <string>

#include "dbc_parser.hpp"

namespace vmass::can::dbc_detail {

void Parser::statement(std::string_view kw) {
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
             kw == "SIG_GROUP_" || kw == "SIG_TYPE_REF_" || kw == "BO_TX_BU_" || kw == "CAT_DEF_" ||
             kw == "CAT_" || kw == "FILTER" || kw == "BU_SG_REL_" || kw == "BU_EV_REL_" ||
             kw == "BU_BO_REL_" || kw == "SIGTYPE_VALTYPE_" || kw == "EV_DATA_" ||
             kw == "BA_DEF_REL_" || kw == "BA_REL_" || kw == "BA_DEF_DEF_REL_" ||
             kw == "BA_DEF_SGTYPE_" || kw == "BA_SGTYPE_" || kw == "NS_DESC_") {
    skip_statement();  // valid statements the decoder has no use for
  } else {
    deviation(statement_line_, "unknown keyword '" + std::string(kw) + "': line skipped");
    skip_line();
  }
}

void Parser::parse_ns() {
  skip_blanks();
  if (peek() == ':') advance();
  skip_line();
  // The symbol list continues on indented lines; the next statement starts in column 1.
  while (!eof() && (peek() == ' ' || peek() == '\t' || peek() == '\r' || peek() == '\n')) {
    skip_line();
  }
}

void Parser::parse_bu() {
  if (!expect(':', "after BU_")) return;
  while (!at_line_end()) {
    std::string node;
    if (!read_name(node, "node name", false)) return;
    db_.nodes.push_back(node);
  }
}

bool Parser::read_message_ref(std::uint32_t& raw_id) {
  std::uint64_t v = 0;
  if (!read_uint(v, "message id")) return false;
  if (v > 0xFFFFFFFFull) return fail("message id above 32 bits");
  raw_id = static_cast<std::uint32_t>(v);
  return true;
}

void Parser::parse_bo() {
  const int line = statement_line_;
  current_message_ = kIgnored;  // until it loads: the signals of a broken BO_ are skipped
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
  if (const auto [it, inserted] = by_name_.emplace(m.name, index); !inserted) {
    deviation(line, "message name " + m.name + " used twice (first at line " +
                        std::to_string(db_.messages[static_cast<std::size_t>(it->second)].line) +
                        ")");
  }
  by_key_[key] = index;
  by_raw_id_[raw_id] = index;
  db_.messages.push_back(std::move(m));
  signal_index_.emplace_back();
  current_message_ = index;
}

void Parser::parse_sg() {
  const int line = statement_line_;
  if (current_message_ == kNone) {
    fail("SG_ outside a BO_ message");
    return;
  }
  Signal sg;
  sg.line = line;
  if (!read_name(sg.name, "signal name")) return;
  skip_blanks();
  if (peek() != ':' && !read_mux_indicator(sg)) return;
  if (!expect(':', "after the signal name")) return;
  std::uint64_t start = 0, length = 0;
  if (!read_uint(start, "start bit")) return;
  if (!expect('|', "between start bit and length")) return;
  if (!read_uint(length, "signal length")) return;
  if (!read_byte_order_and_sign(sg) || !read_scaling(sg)) return;
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
  const auto msg = static_cast<std::size_t>(current_message_);
  Message& m = db_.messages[msg];
  if (m.signals.size() >= kMaxSignalsPerMessage) {
    // One error per message, at its first signal left out: not one per signal.
    if (signals_left_out_.insert(msg).second) {
      error_at(line, "signal " + sg.name + ": message " + m.name + " has more than " +
                         std::to_string(kMaxSignalsPerMessage) +
                         " signals (vmass reads at most that many; the rest are left out)");
    }
    return;
  }
  signal_index_[msg].emplace(sg.name, static_cast<int>(m.signals.size()));
  m.signals.push_back(std::move(sg));
}

void Parser::index_signals(std::size_t msg) {
  std::unordered_map<std::string, int>& index = signal_index_[msg];
  index.clear();
  const std::vector<Signal>& signals = db_.messages[msg].signals;
  for (std::size_t i = 0; i < signals.size(); ++i) {
    index.emplace(signals[i].name, static_cast<int>(i));  // the first of a name, as find_signal
  }
}

bool Parser::read_mux_indicator(Signal& sg) {
  const std::size_t begin = pos_;
  const std::string_view mux = read_word();
  if (mux == "M") {
    sg.is_multiplexor = true;
    return true;
  }
  if (mux == "m") {  // real files write the switch so, with its pages as m2, m3 after it
    deviation(statement_line_,
              "signal " + sg.name + ": multiplexer switch written as a lone 'm'; read as 'M'");
    sg.is_multiplexor = true;
    return true;
  }
  if (mux.size() >= 2 && mux[0] == 'm' && is_digit(mux[1])) {
    std::size_t e = 1;
    while (e < mux.size() && is_digit(mux[e])) ++e;
    std::uint64_t v = 0;
    if (std::from_chars(mux.data() + 1, mux.data() + e, v).ec != std::errc()) {
      pos_ = begin;
      return fail("multiplexer value above 64 bits");
    }
    sg.mux_value = v;
    if (e == mux.size()) return true;
    if (mux.substr(e) == "M") {
      sg.is_multiplexor = true;
      return true;
    }
  }
  pos_ -= mux.size();
  return fail("expected multiplexer indicator (M, mNN or mNNM) or ':'");
}

bool Parser::read_byte_order_and_sign(Signal& sg) {
  if (!expect('@', "before the byte order")) return false;
  if (peek() == '0') {
    sg.byte_order = ByteOrder::kMotorola;
  } else if (peek() == '1') {
    sg.byte_order = ByteOrder::kIntel;
  } else {
    return fail("expected byte order 0 (Motorola) or 1 (Intel) after '@'");
  }
  advance();
  if (peek() != '+' && peek() != '-') return fail("expected sign '+' or '-' after the byte order");
  sg.is_signed = peek() == '-';
  advance();
  return true;
}

bool Parser::read_scaling(Signal& sg) {
  if (!expect('(', "before factor") || !read_double(sg.factor, "factor") ||
      !expect(',', "between factor and offset") || !read_double(sg.offset, "offset") ||
      !expect(')', "after offset") || !expect('[', "before minimum") ||
      !read_double(sg.minimum, "minimum") || !expect('|', "between minimum and maximum") ||
      !read_double(sg.maximum, "maximum") || !expect(']', "after maximum")) {
    return false;
  }
  sg.has_range = !(sg.minimum == 0.0 && sg.maximum == 0.0);
  if (sg.factor == 0.0) {
    deviation(statement_line_, "signal " + sg.name + ": factor 0: its value is always the offset");
  }
  if (sg.has_range && sg.minimum > sg.maximum) {
    deviation(statement_line_, "signal " + sg.name + ": minimum above maximum; range ignored");
    sg.has_range = false;
  }
  return true;
}

int Parser::message_for(std::uint32_t raw_id, const char* statement) {
  if (const auto it = by_raw_id_.find(raw_id); it != by_raw_id_.end()) return it->second;
  if (ignored_ids_.count(raw_id) != 0) return -2;
  deviation(statement_line_,
            std::string(statement) + " refers to unknown message id " + std::to_string(raw_id));
  return -1;
}

Signal* Parser::signal_for(int msg, const std::string& name, const char* statement) {
  if (msg < 0) return nullptr;
  Message& m = db_.messages[static_cast<std::size_t>(msg)];
  const auto& index = signal_index_[static_cast<std::size_t>(msg)];
  const auto found = index.find(name);
  const int i = found == index.end() ? -1 : found->second;
  if (i < 0) {
    deviation(statement_line_, std::string(statement) + " refers to unknown signal " + name +
                                   " of message " + m.name);
    return nullptr;
  }
  return &m.signals[static_cast<std::size_t>(i)];
}

void Parser::parse_cm() {
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

bool Parser::read_value_pairs(std::vector<ValueDescription>& out, const char* statement) {
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
    // The key is an int64: a value outside [-2^63, 2^63) cannot be converted (undefined
    // behaviour, found by fuzz_dbc_parser) and describes no raw value that key could hold.
    constexpr double kInt64Bound = 9223372036854775808.0;  // 2^63, exact as a double
    if (!(v >= -kInt64Bound && v < kInt64Bound)) {
      char shown[32];
      std::snprintf(shown, sizeof shown, "%g", v);
      deviation(statement_line_, std::string(statement) + " value " + shown +
                                     " is outside the 64-bit integer range; left out");
      if (!read_string(d.text, "value description")) return false;
      continue;
    }
    d.value = static_cast<std::int64_t>(v);
    if (static_cast<double>(d.value) != v) {
      deviation(statement_line_, std::string(statement) + " value " + std::to_string(v) +
                                     " is not an integer; truncated");
    }
    if (!read_string(d.text, "value description")) return false;
    out.push_back(std::move(d));
  }
}

void Parser::parse_val() {
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

void Parser::parse_val_table() {
  ValueTable t;
  if (!read_name(t.name, "value table name")) return;
  if (!read_value_pairs(t.values, "VAL_TABLE_")) return;
  db_.value_tables.push_back(std::move(t));
}

bool Parser::read_attribute_value(std::string& out) {
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

void Parser::parse_ba_def() {
  AttributeDefinition def;
  skip_ws();
  if (peek() != '"') {
    const std::size_t p = pos_;
    def.object = std::string(read_word());
    if (def.object != "BU_" && def.object != "BO_" && def.object != "SG_" && def.object != "EV_") {
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

AttributeDefinition* Parser::attribute(const std::string& name) {
  for (auto& a : db_.attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

void Parser::parse_ba_def_def() {
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

void Parser::parse_ba() {
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

void Parser::apply_message_attribute(Message& m, const std::string& name,
                                     const std::string& value) {
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

bool Parser::frame_format_is_fd(const std::string& value) {
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

void Parser::parse_sig_valtype() {
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

void Parser::parse_sg_mul_val() {
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
    if (e.ranges.size() >= kMaxMuxRanges) {
      error_at(e.line, "SG_MUL_VAL_ " + e.signal + ": more than " + std::to_string(kMaxMuxRanges) +
                           " ranges (vmass reads at most that many)");
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

}  // namespace vmass::can::dbc_detail
