#include "vmass/config/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>
#include <string_view>

#include "vmass/io/excerpt.hpp"

namespace vmass {
namespace {

// Locale-free number parsing, with YAML's spellings of infinity and NaN.
bool parse_double(const std::string& text, double* out) {
  if (text == ".inf" || text == ".Inf" || text == ".INF" || text == "+.inf" || text == "inf") {
    *out = std::numeric_limits<double>::infinity();
    return true;
  }
  if (text == "-.inf" || text == "-.Inf" || text == "-.INF" || text == "-inf") {
    *out = -std::numeric_limits<double>::infinity();
    return true;
  }
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double v = 0.0;
  in >> v;
  if (in.fail()) return false;
  in >> std::ws;
  if (!in.eof()) return false;  // trailing characters: "12abc"
  *out = v;
  return true;
}

/// The largest magnitude a number may have for the unit its key ends in: beyond it the value
/// means nothing physical and only overflows what is computed from it (1e300 kg, a timeout of
/// 1e13 s whose microseconds do not fit in 64 bits). Infinities are left to the validation of
/// the keys that allow them.
struct UnitBound {
  const char* suffix;
  double max_abs;
  const char* unit;
};
constexpr UnitBound kUnitBounds[] = {
    {"_s", 1e6, "s"},
    {"_hz", 1e6, "Hz"},
    {"_kg", 1e7, "kg"},
    {"_m", 1e4, "m"},
    {"_m2", 1e4, "m^2"},
    {"_mps", 1e4, "m/s"},
    {"_mps2", 1e4, "m/s^2"},
    {"_n", 1e9, "N"},
    {"_nm", 1e9, "N m"},
    {"_pa", 1e10, "Pa"},
    {"_n_per_m", 1e10, "N/m"},
    {"_n_per_m2", 1e12, "N/m^2"},
    {"_n_per_rad", 1e9, "N/rad"},
    {"_n_per_pa", 1e3, "N/Pa"},
    {"_deg", 1e6, "deg"},
    {"_rad", 1e4, "rad"},
    {"_radps", 1e4, "rad/s"},
    {"_kg_per_m3", 1e4, "kg/m^3"},
};

const UnitBound* unit_bound(const std::string& key) {
  const UnitBound* best = nullptr;  // the longest matching suffix: _n_per_m before _m
  for (const UnitBound& b : kUnitBounds) {
    const std::string_view suffix(b.suffix);
    if (key.size() > suffix.size() &&
        key.compare(key.size() - suffix.size(), suffix.size(), suffix.data(), suffix.size()) == 0) {
      if (best == nullptr || suffix.size() > std::string_view(best->suffix).size()) best = &b;
    }
  }
  return best;
}

std::string number_text(double v) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << v;
  return s.str();
}

}  // namespace

YamlReader::YamlReader(YAML::Node node, std::string file, std::string path)
    : node_(node), file_(std::move(file)), path_(std::move(path)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    std::ostringstream msg;
    msg << file_ << ":" << line_of(node_) << ": " << (path_.empty() ? "<top>" : path_)
        << ": expected a map of keys";
    throw ConfigError(msg.str());
  }
}

int YamlReader::line_of(const YAML::Node& n) const { return n.Mark().line + 1; }

std::string YamlReader::full_key(const std::string& key) const {
  if (key.empty()) return path_;  // the section itself
  return path_.empty() ? key : path_ + "." + key;
}

void YamlReader::fail(const std::string& key, const std::string& message) const {
  std::ostringstream msg;
  YAML::Node n = value_node(key);
  msg << file_;
  if (n) {
    msg << ":" << line_of(n);
  } else if (node_ && node_.IsMap()) {
    msg << ":" << line_of(node_);
  }
  msg << ": " << full_key(key) << ": " << message;
  throw ConfigError(msg.str());
}

bool YamlReader::has(const std::string& key) const {
  return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
}

void YamlReader::refuse_null(const std::string& key) const {
  // A key written with no value, or ~, is YAML's null: never taken for "use the default".
  if (node_ && node_.IsMap() && node_[key] && node_[key].IsNull()) {
    std::ostringstream msg;
    msg << file_ << ":" << line_of(node_[key]) << ": " << io::excerpt(full_key(key))
        << ": no value (null, '~' or empty): write one, or leave the key out for its default";
    throw ConfigError(msg.str());
  }
}

YAML::Node YamlReader::value_node(const std::string& key) const {
  if (!node_ || !node_.IsMap()) return YAML::Node();
  return node_[key];
}

void YamlReader::read(const std::string& key, double* out) {
  used_.push_back(key);
  refuse_null(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsScalar() || !parse_double(n.Scalar(), out) || std::isnan(*out)) {
    fail(key, "expected a number, got '" +
                  (n.IsScalar() ? io::excerpt(n.Scalar()) : std::string("<map>")) + "'");
  }
  const UnitBound* bound = unit_bound(key);
  if (bound != nullptr && std::isfinite(*out) && std::abs(*out) > bound->max_abs) {
    fail(key, number_text(*out) + " is beyond any plausible value (|x| <= " +
                  number_text(bound->max_abs) + " " + bound->unit + ")");
  }
}

void YamlReader::read(const std::string& key, int* out) {
  double v = 0.0;
  const bool present = has(key);
  read(key, &v);
  if (!present) return;
  if (!(std::abs(v) < 2e9) || v != std::floor(v)) fail(key, "expected an integer");
  *out = static_cast<int>(v);
}

void YamlReader::read(const std::string& key, long* out) {
  double v = 0.0;
  const bool present = has(key);
  read(key, &v);
  if (!present) return;
  if (!(std::abs(v) < 9e15) || v != std::floor(v)) fail(key, "expected an integer");
  *out = static_cast<long>(v);
}

void YamlReader::read(const std::string& key, bool* out) {
  used_.push_back(key);
  refuse_null(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  const std::string s = n.IsScalar() ? io::excerpt(n.Scalar()) : "";
  if (s == "true" || s == "True" || s == "yes" || s == "on") {
    *out = true;
  } else if (s == "false" || s == "False" || s == "no" || s == "off") {
    *out = false;
  } else {
    fail(key, "expected true or false, got '" + s + "'");
  }
}

void YamlReader::read(const std::string& key, std::string* out) {
  used_.push_back(key);
  refuse_null(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsScalar()) fail(key, "expected a string");
  *out = n.Scalar();
}

void YamlReader::read(const std::string& key, std::vector<double>* out) {
  used_.push_back(key);
  refuse_null(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsSequence()) fail(key, "expected a list of numbers");
  out->clear();
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0.0;
    if (!n[i].IsScalar() || !parse_double(n[i].Scalar(), &v) || std::isnan(v)) {
      fail(key, "element " + std::to_string(i) + " is not a number");
    }
    const UnitBound* bound = unit_bound(key);
    if (bound != nullptr && !(std::abs(v) <= bound->max_abs)) {
      fail(key, "element " + std::to_string(i) + ": " + number_text(v) +
                    " is beyond any plausible value (|x| <= " + number_text(bound->max_abs) + " " +
                    bound->unit + ")");
    }
    out->push_back(v);
  }
}

void YamlReader::read(const std::string& key, std::vector<int>* out) {
  std::vector<double> values;
  const bool present = has(key);
  read(key, &values);
  if (!present) return;
  out->clear();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(std::abs(values[i]) < 2e9) || values[i] != std::floor(values[i])) {
      fail(key, "element " + std::to_string(i) + " is not an integer");
    }
    out->push_back(static_cast<int>(values[i]));
  }
}

void YamlReader::require(const std::string& key, double* out) {
  if (!has(key)) fail(key, "required key is missing");
  read(key, out);
}

void YamlReader::require(const std::string& key, std::string* out) {
  if (!has(key)) fail(key, "required key is missing");
  read(key, out);
}

YamlReader YamlReader::child(const std::string& key) {
  used_.push_back(key);
  return YamlReader(has(key) ? value_node(key) : YAML::Node(), file_, full_key(key));
}

YAML::Node YamlReader::raw(const std::string& key) {
  used_.push_back(key);
  return has(key) ? value_node(key) : YAML::Node();  // never a yaml-cpp "zombie" node
}

void YamlReader::reject_unknown_keys() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(used_.begin(), used_.end(), key) == used_.end()) {
      std::ostringstream msg;
      msg << file_ << ":" << line_of(kv.first) << ": " << io::excerpt(full_key(key))
          << ": unknown key";
      throw ConfigError(msg.str());
    }
  }
}

}  // namespace vmass
