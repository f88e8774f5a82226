#include "vmass/config/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>

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

YAML::Node YamlReader::value_node(const std::string& key) const {
  if (!node_ || !node_.IsMap()) return YAML::Node();
  return node_[key];
}

void YamlReader::read(const std::string& key, double* out) {
  used_.push_back(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsScalar() || !parse_double(n.Scalar(), out) || std::isnan(*out)) {
    fail(key,
         "expected a number, got '" + (n.IsScalar() ? n.Scalar() : std::string("<map>")) + "'");
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

void YamlReader::read(const std::string& key, bool* out) {
  used_.push_back(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  const std::string s = n.IsScalar() ? n.Scalar() : "";
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
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsScalar()) fail(key, "expected a string");
  *out = n.Scalar();
}

void YamlReader::read(const std::string& key, std::vector<double>* out) {
  used_.push_back(key);
  if (!has(key)) return;
  YAML::Node n = value_node(key);
  if (!n.IsSequence()) fail(key, "expected a list of numbers");
  out->clear();
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0.0;
    if (!n[i].IsScalar() || !parse_double(n[i].Scalar(), &v)) {
      fail(key, "element " + std::to_string(i) + " is not a number");
    }
    out->push_back(v);
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
      msg << file_ << ":" << line_of(kv.first) << ": " << full_key(key) << ": unknown key";
      throw ConfigError(msg.str());
    }
  }
}

}  // namespace vmass
