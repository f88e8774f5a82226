#include "vmass/signals/message_protection.hpp"

#include <charconv>

#include "vmass/config/yaml_reader.hpp"
#include "vmass/io/excerpt.hpp"

namespace vmass::signals {
namespace {

std::string quoted(const std::string& s) { return "'" + io::excerpt(s) + "'"; }

/// A signal of the message for `key`, which must be an unsigned integer field.
can::SignalRef find_field(YamlReader& r, const std::string& key, const can::Decoder& d, int m) {
  std::string name;
  r.read(key, &name);
  const can::Message& msg = d.database().messages[static_cast<std::size_t>(m)];
  const int s = msg.find_signal(name);
  if (s < 0) r.fail(key, "message " + msg.name + " has no signal " + quoted(name));
  const can::Signal& sig = msg.signals[static_cast<std::size_t>(s)];
  if (sig.is_signed || sig.value_type != can::ValueType::kInteger || sig.mux_parent >= 0) {
    r.fail(key, msg.name + "." + sig.name + " must be an unsigned, unmultiplexed integer");
  }
  return can::SignalRef{m, s};
}

/// data_id: a number 0..0xFFFF (decimal or 0x hex), or id_low_byte.
void read_data_id(YamlReader& r, const can::Message& msg, can::E2eProfile* p) {
  if (!r.has("data_id")) return;
  std::string text;
  r.read("data_id", &text);
  p->has_data_id = true;
  if (text == "id_low_byte") {
    p->data_id = msg.id & 0xFFu;
    return;
  }
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const char* begin = text.data() + (hex ? 2 : 0);
  const char* end = text.data() + text.size();
  unsigned long v = 0;
  const auto res = std::from_chars(begin, end, v, hex ? 16 : 10);
  if (res.ec != std::errc() || res.ptr != end || v > 0xFFFFu) {
    r.fail("data_id", "expected a number 0..0xFFFF or id_low_byte, got " + quoted(text));
  }
  p->data_id = static_cast<std::uint32_t>(v);
}

/// bytes: [first, last] within the message; default: all but the checksum signal's bytes.
void read_bytes(YamlReader& r, const can::Decoder& d, const can::Message& msg, can::E2eProfile* p) {
  const int length = msg.length;
  std::uint64_t all = length >= 64 ? ~0ull : (1ull << length) - 1;
  if (!r.has("bytes")) {
    if (p->checksum.valid()) {
      const can::CompiledSignal& c = d.compiled(p->checksum);
      for (int b = 0; b < c.byte_count; ++b) {
        // Motorola signals run from first_byte up too (big-endian assembly).
        all &= ~(1ull << (c.first_byte + b));
      }
    }
    p->covered_bytes = all;
    return;
  }
  std::vector<double> range;
  r.read("bytes", &range);
  if (range.size() != 2 || range[0] != static_cast<int>(range[0]) ||
      range[1] != static_cast<int>(range[1]) ||
      !(range[0] >= 0 && range[0] <= range[1] && range[1] < length)) {
    r.fail("bytes", "expected [first, last] with 0 <= first <= last < " + std::to_string(length) +
                        " (the bytes of " + msg.name + ")");
  }
  p->covered_bytes = 0;
  for (int b = static_cast<int>(range[0]); b <= static_cast<int>(range[1]); ++b) {
    p->covered_bytes |= 1ull << b;
  }
}

void read_checksum(YamlReader& r, const can::Decoder& d, int m, can::E2eProfile* p) {
  p->checksum = find_field(r, "checksum", d, m);
  std::string name;
  r.require("algorithm", &name);
  const can::ChecksumAlgorithm* a = can::find_checksum(name);
  if (a == nullptr) {
    r.fail("algorithm",
           "unknown checksum " + quoted(name) + " (known: " + can::checksum_names() + ")");
  }
  const int bits = d.compiled(p->checksum).length;
  if (a->required_bits != 0 && bits != a->required_bits) {
    r.fail("checksum", "algorithm " + name + " needs a " + std::to_string(a->required_bits) +
                           "-bit checksum signal, this one has " + std::to_string(bits));
  }
  p->algorithm = a->compute;
}

ProtectedMessage parse_message(YamlReader& r, const std::string& name, const can::Decoder& d,
                               const std::string& dbc_name) {
  ProtectedMessage out;
  out.message = d.find_message(name);
  if (out.message < 0) r.fail("", "no message " + quoted(name) + " in " + dbc_name);
  const can::Message& msg = d.database().messages[static_cast<std::size_t>(out.message)];
  can::E2eProfile& p = out.profile;
  if (!r.has("counter") && !r.has("checksum")) {
    r.fail("", "give a counter:, a checksum: or both");
  }
  if (r.has("counter")) {
    p.counter = find_field(r, "counter", d, out.message);
    int step = 1;
    r.read("max_counter_step", &step);
    const std::uint64_t largest = d.compiled(p.counter).mask;  // 2^length - 1
    if (step < 1 || static_cast<std::uint64_t>(step) > largest) {
      r.fail("max_counter_step", "must be in [1, " + std::to_string(largest) + "]");
    }
    p.max_counter_step = static_cast<std::uint32_t>(step);
  }
  if (r.has("checksum")) {
    read_checksum(r, d, out.message, &p);
    read_data_id(r, msg, &p);
  }
  read_bytes(r, d, msg, &p);
  r.reject_unknown_keys();
  return out;
}

}  // namespace

const can::E2eProfile* MessageProtection::find(int message) const {
  for (const ProtectedMessage& m : messages) {
    if (m.message == message) return &m.profile;
  }
  return nullptr;
}

std::string parse_message_protection(const YAML::Node& e2e, const std::string& file,
                                     const can::Decoder& decoder, const std::string& dbc_name,
                                     MessageProtection* out) {
  try {
    YamlReader r(e2e, file, "can.e2e");
    MessageProtection p;
    r.read("invalid_after", &p.invalid_after);
    r.read("valid_after", &p.valid_after);
    if (p.invalid_after < 1 || p.invalid_after > 1000) r.fail("invalid_after", "must be 1..1000");
    if (p.valid_after < 1 || p.valid_after > 1000) r.fail("valid_after", "must be 1..1000");
    YamlReader messages = r.child("messages");
    const YAML::Node list = r.raw("messages");
    if (list && list.IsMap()) {
      for (const auto& kv : list) {
        const std::string name = kv.first.as<std::string>();
        YamlReader m = messages.child(name);
        if (p.find(decoder.find_message(name)) != nullptr) m.fail("", "listed twice");
        p.messages.push_back(parse_message(m, name, decoder, dbc_name));
      }
    }
    r.reject_unknown_keys();
    *out = std::move(p);
    return "";
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const YAML::Exception& e) {
    return file + ":" + std::to_string(e.mark.line + 1) + ": can.e2e: " + e.msg;
  }
}

}  // namespace vmass::signals
