#include "vmass/signals/signal_mapping.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "vmass/can/dbc.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/io/excerpt.hpp"
#include "vmass/signals/torque_path_check.hpp"
#include "vmass/signals/units.hpp"

namespace vmass::signals {
namespace {

std::string quoted(const std::string& s) { return "'" + io::excerpt(s) + "'"; }

/// Messages of the DBC named `name` (a DBC from many hands may name two alike).
int count_named(const can::Database& db, const std::string& name) {
  int n = 0;
  for (const can::Message& m : db.messages) n += m.name == name;
  return n;
}

std::string input_names() {
  std::string s;
  for (int i = 0; i < kInputCount; ++i) {
    if (i > 0) s += ", ";
    s += input_name(static_cast<Input>(i));
  }
  return s;
}

// "1, 3..4" for a signal's mux ranges.
std::string pages(const can::Signal& sig) {
  std::string s;
  for (const can::MuxRange& r : sig.mux_ranges) {
    if (!s.empty()) s += ", ";
    s += std::to_string(r.lo);
    if (r.hi != r.lo) s += ".." + std::to_string(r.hi);
  }
  return s;
}

// "an acceleration", "a speed".
std::string with_article(std::string_view noun) {
  const bool vowel =
      !noun.empty() && std::string_view("aeiou").find(noun[0]) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(noun);
}

double default_timeout_s(int cycle_time_ms) {
  return cycle_time_ms > 0 ? 5.0 * cycle_time_ms / 1000.0 : 0.1;
}

/// A message or signal name that differs only in case, as a hint.
template <class Items, class NameOf>
std::string case_hint(const Items& items, const std::string& wanted, NameOf name_of) {
  auto lower = [](std::string s) {
    for (char& c : s) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    return s;
  };
  const std::string w = lower(wanted);
  for (const auto& item : items) {
    if (lower(name_of(item)) == w) return " (did you mean " + quoted(name_of(item)) + "?)";
  }
  return "";
}

struct TermContext {
  Input input;
  const can::Decoder& decoder;
  const std::string& dbc_name;
  bool timeout_given = false;
  double timeout_s = 0.0;
};

/// The page of a multiplexed signal (mux:): must be named, and must select the signal.
void read_mux(YamlReader& t, const can::Message& msg, const can::Signal& sig, int m,
              const std::string& what, MappedSignal* out) {
  const bool has_mux = t.has("mux");
  int mux = 0;
  t.read("mux", &mux);
  if (sig.mux_parent < 0) {
    if (has_mux) t.fail("mux", "signal " + quoted(what) + " is not multiplexed; remove mux:");
    return;
  }
  const can::Signal& sw = msg.signals[static_cast<std::size_t>(sig.mux_parent)];
  if (!has_mux) {
    t.fail("mux", "signal " + quoted(what) + " is multiplexed by " + quoted(sw.name) + " (pages " +
                      pages(sig) + "): give the page to accept, e.g. mux: " +
                      std::to_string(sig.mux_ranges.empty() ? 0 : sig.mux_ranges[0].lo));
  }
  bool selects = false;
  for (const can::MuxRange& r : sig.mux_ranges) {
    if (mux >= 0 && static_cast<std::uint64_t>(mux) >= r.lo &&
        static_cast<std::uint64_t>(mux) <= r.hi) {
      selects = true;
    }
  }
  if (!selects) {
    t.fail("mux", sw.name + " = " + std::to_string(mux) + " does not select " + quoted(what) +
                      " (pages " + pages(sig) + ")");
  }
  out->mux_switch = can::SignalRef{m, sig.mux_parent};
  out->mux_value = static_cast<std::uint64_t>(mux);
}

/// Units: the DBC's (or the unit: override), converted to SI by the table; gain: on top, or
/// the whole conversion for a unit the table does not know.
void read_units(YamlReader& t, const can::Signal& sig, Input input, const std::string& what,
                MappedSignal* out) {
  const bool has_unit = t.has("unit");
  out->unit = sig.unit;
  t.read("unit", &out->unit);
  const bool has_gain = t.has("gain");
  t.read("gain", &out->gain);
  if (has_gain && !(std::isfinite(out->gain) && out->gain != 0.0)) {
    t.fail("gain", "must be a finite number other than 0");
  }
  const Dimension need = input_dimension(input);
  const std::string unit_key = has_unit ? "unit" : "signal";
  const std::string source = has_unit            ? "unit " + quoted(out->unit)
                             : out->unit.empty() ? what + " has no unit"
                                                 : what + " has unit " + quoted(out->unit);
  std::optional<UnitConversion> conv = find_unit(out->unit);
  const bool unitless = conv && conv->dimension == Dimension::kDimensionless;
  if (unitless && need != Dimension::kDimensionless) {
    conv.reset();  // a unitless signal for a physical input: its conversion must be given
  }
  if (conv) {
    if (conv->dimension != need) {
      t.fail(unit_key, source + ", " + with_article(dimension_name(conv->dimension)) + "; " +
                           std::string(input_name(input)) + " needs " +
                           with_article(dimension_name(need)) + " (" + units_of(need) + ")" +
                           (has_unit ? "" : "; unit: overrides the DBC's unit"));
    }
    out->unit_scale = conv->scale;
  } else if (!has_gain) {
    t.fail(unit_key, source + (unitless ? "" : ", which is not in the unit table") +
                         ": give gain: (" + std::string(si_unit(need)) +
                         " per DBC unit) or unit: (one of " + units_of(need) + ")");
  } else {
    out->unit_scale = 1.0;  // the gain is the whole conversion
  }
}

MappedSignal parse_term(YamlReader& t, const TermContext& ctx) {
  MappedSignal out;
  t.require("message", &out.message);
  t.require("signal", &out.signal);
  const can::Database& db = ctx.decoder.database();
  const int m = ctx.decoder.find_message(out.message);
  if (m < 0) {
    t.fail("message",
           "no message " + quoted(out.message) + " in " + ctx.dbc_name +
               case_hint(db.messages, out.message, [](const can::Message& x) { return x.name; }));
  }
  if (count_named(db, out.message) > 1) {
    t.fail("message", quoted(out.message) + " names " +
                          std::to_string(count_named(db, out.message)) + " messages in " +
                          ctx.dbc_name + ": rename them in the DBC");
  }
  const can::Message& msg = db.messages[static_cast<std::size_t>(m)];
  const int s = msg.find_signal(out.signal);
  if (s < 0) {
    t.fail("signal",
           "message " + quoted(out.message) + " has no signal " + quoted(out.signal) +
               case_hint(msg.signals, out.signal, [](const can::Signal& x) { return x.name; }));
  }
  const can::Signal& sig = msg.signals[static_cast<std::size_t>(s)];
  out.ref = can::SignalRef{m, s};
  const std::string what = out.message + "." + out.signal;
  if (sig.factor == 0.0) {
    t.fail("signal", what + " has factor 0 in " + ctx.dbc_name +
                         ": its value is always its offset; fix the DBC");
  }
  read_mux(t, msg, sig, m, what, &out);
  read_units(t, sig, ctx.input, what, &out);
  out.has_range = sig.has_range;
  out.minimum = sig.minimum;
  out.maximum = sig.maximum;
  out.cycle_time_ms = msg.cycle_time_ms;
  out.timeout_s = ctx.timeout_given ? ctx.timeout_s : default_timeout_s(msg.cycle_time_ms);
  t.reject_unknown_keys();
  return out;
}

InputMapping parse_input(YamlReader& r, Input input, const can::Decoder& decoder,
                         const std::string& dbc_name, const std::string& file) {
  InputMapping out;
  out.input = input;
  TermContext ctx{input, decoder, dbc_name};
  ctx.timeout_given = r.has("timeout_s");
  r.read("timeout_s", &ctx.timeout_s);
  if (ctx.timeout_given && !(ctx.timeout_s > 0.0 && std::isfinite(ctx.timeout_s))) {
    r.fail("timeout_s", "must be a finite number > 0");
  }
  r.read("offset", &out.offset);
  if (!std::isfinite(out.offset)) r.fail("offset", "must be a finite number");
  if (r.has("sum")) {
    for (const char* key : {"message", "signal", "mux", "unit", "gain"}) {
      if (r.has(key)) r.fail(key, "not allowed beside sum: (give it in each term)");
    }
    out.is_sum = true;
    const YAML::Node list = r.raw("sum");
    if (!list.IsSequence() || list.size() == 0) {
      r.fail("sum", "expected a non-empty list of {message, signal, gain}");
    }
    for (std::size_t j = 0; j < list.size(); ++j) {
      if (!list[j].IsMap()) {
        r.fail("sum", "element " + std::to_string(j) + " must be a map {message, signal, gain}");
      }
      YamlReader t(list[j], file, r.full_key("sum") + "[" + std::to_string(j) + "]");
      out.terms.push_back(parse_term(t, ctx));
    }
    r.reject_unknown_keys();
  } else {
    out.terms.push_back(parse_term(r, ctx));  // also rejects unknown keys
  }
  return out;
}

}  // namespace

const InputMapping* SignalMapping::find(Input input) const {
  for (const InputMapping& m : inputs) {
    if (m.input == input) return &m;
  }
  return nullptr;
}

std::string SignalMapping::describe() const {
  std::ostringstream os;
  for (const InputMapping& m : inputs) {
    os << input_name(m.input) << " <-";
    for (std::size_t j = 0; j < m.terms.size(); ++j) {
      const MappedSignal& t = m.terms[j];
      char buf[96];
      std::snprintf(buf, sizeof buf, " [%s x %.6g] timeout %.3g s", t.unit.c_str(), t.scale(),
                    t.timeout_s);
      os << (j > 0 ? " +" : "") << " " << t.message << "." << t.signal;
      if (t.mux_switch.valid()) os << "(mux " << t.mux_value << ")";
      os << buf;
    }
    if (m.offset != 0.0) os << " + " << m.offset;
    os << "\n";
  }
  return os.str();
}

std::string parse_signal_mapping(const YAML::Node& inputs, const std::string& file,
                                 const can::Decoder& decoder, const std::string& dbc_name,
                                 SignalMapping* out) {
  try {
    YamlReader r(inputs, file, "can.inputs");
    SignalMapping mapping;
    for (int i = 0; i < kInputCount; ++i) {
      const auto input = static_cast<Input>(i);
      const std::string name(input_name(input));
      if (inputs && inputs.IsMap() && inputs[name] && inputs[name].IsNull()) {
        for (const auto& kv : inputs) {  // a null value has no line of its own: the key's
          if (kv.first.as<std::string>() == name) {
            throw ConfigError(file + ":" + std::to_string(kv.first.Mark().line + 1) + ": " +
                              r.full_key(name) + ": expected {message, signal} or {sum: [...]}");
          }
        }
      }
      if (!r.has(name)) continue;
      YamlReader child = r.child(name);
      mapping.inputs.push_back(parse_input(child, input, decoder, dbc_name, file));
    }
    if (inputs && inputs.IsMap()) {
      for (const auto& kv : inputs) {
        const std::string key = kv.first.as<std::string>();
        bool known = false;
        for (int i = 0; i < kInputCount; ++i) {
          if (key == input_name(static_cast<Input>(i))) known = true;
        }
        if (!known) r.fail(key, "unknown input (known: " + input_names() + ")");
      }
    }
    *out = std::move(mapping);
    return "";
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const YAML::Exception& e) {
    return file + ":" + std::to_string(e.mark.line + 1) + ": can.inputs: " + e.msg;
  }
}

CanInputsLoad load_can_inputs(const Config& config) {
  CanInputsLoad out;
  try {
    if (!config.can || config.can.IsNull()) {
      out.error = config.file +
                  ": can: required section is missing (CAN input needs can.dbc and can.inputs)";
      return out;
    }
    YamlReader r(config.can, config.file, "can");
    std::string dbc;
    r.require("dbc", &dbc);
    const YAML::Node inputs = r.raw("inputs");
    const YAML::Node e2e = r.raw("e2e");
    const YAML::Node plausibility = r.raw("plausibility");
    bool enforce_dbc_ranges = false;
    r.read("enforce_dbc_ranges", &enforce_dbc_ranges);
    r.reject_unknown_keys();

    CanInputs result;
    result.dbc_path = config.resolve_path(dbc);
    can::DbcParseResult parsed = can::load_dbc_file(result.dbc_path);
    for (const can::DbcDiagnostic& d : parsed.diagnostics) {
      if (d.severity == can::Severity::kError) {
        const int errors = parsed.error_count();
        r.fail("dbc",
               d.to_string() +
                   (errors > 1 ? " (and " + std::to_string(errors - 1) + " more errors)" : ""));
      }
      result.warnings.push_back(d.to_string());
    }
    std::string error;
    std::optional<can::Decoder> decoder = can::Decoder::compile(std::move(parsed.database), &error);
    if (!decoder) r.fail("dbc", result.dbc_path + ": " + error);
    result.decoder = std::make_shared<const can::Decoder>(std::move(*decoder));
    SignalMapping& mapping = result.mapping;
    error = parse_signal_mapping(inputs, config.file, *result.decoder, dbc, &mapping);
    if (error.empty()) {
      error = parse_message_protection(e2e, config.file, *result.decoder, dbc, &mapping.protection);
    }
    if (error.empty()) error = parse_plausibility(plausibility, config.file, &mapping.plausibility);
    if (error.empty()) error = check_torque_path(config, mapping);
    if (!error.empty()) {
      out.error = error;
      return out;
    }
    mapping.enforce_dbc_ranges = enforce_dbc_ranges;
    out.inputs = std::move(result);
  } catch (const ConfigError& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace vmass::signals
