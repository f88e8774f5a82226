#include "vmass/config/config.hpp"

#include <algorithm>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include "vmass/config/estimator_section.hpp"
#include "vmass/config/suspension_section.hpp"
#include "vmass/config/vehicle_section.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/config/yaml_tree.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass {
namespace {

/// PipelineParams::validate()'s "key what; key what" as "file:line: key: what" lines, the line
/// being where the key is written (or its section, for a key left at its default).
std::string located(const std::string& invalid, const YAML::Node& root, const std::string& file) {
  std::string out;
  std::size_t begin = 0;
  while (begin < invalid.size()) {
    std::size_t end = invalid.find("; ", begin);
    if (end == std::string::npos) end = invalid.size();
    const std::string one = invalid.substr(begin, end - begin);
    const std::size_t space = one.find(' ');
    std::string key = one.substr(0, space);
    int line = line_of_key(root, key);
    // The estimator's sub-sections name their keys from the section down ("rls.forgetting_factor").
    if (line == 0 && line_of_key(root, "estimator." + key) > 0) {
      key = "estimator." + key;
      line = line_of_key(root, key);
    }
    if (!out.empty()) out += "\n";
    out += file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + key + ":" +
           (space == std::string::npos ? "" : one.substr(space));
    begin = end + 2;
  }
  return out;
}

/// can.inputs maps a wheel torque: the torque input, whatever ratios the vehicle gives.
bool maps_wheel_torque(const YAML::Node& can) {
  if (!can.IsDefined() || !can.IsMap()) return false;
  // Const access: a missing key reads as undefined and is not inserted.
  const YAML::Node inputs = can["inputs"];
  return inputs.IsDefined() && inputs.IsMap() && inputs["wheel_torque"].IsDefined();
}

ConfigLoad parse(const YAML::Node& root, const std::string& file, const std::string& directory) {
  ConfigLoad out;
  try {
    if (std::string duplicate = duplicate_key_error(root, file); !duplicate.empty()) {
      out.error = std::move(duplicate);
      return out;
    }
    Config c;
    c.file = file;
    c.directory = directory;
    YamlReader top(root, file, "");
    if (!top.has("vehicle")) top.fail("vehicle", "required section is missing");
    read_vehicle_section(top.child("vehicle"), &c.pipeline.vehicle);
    const bool has_suspension = top.has("suspension");
    read_suspension_section(top.child("suspension"), has_suspension, &c.pipeline.suspension);
    read_estimator_section(top.child("estimator"), &c.pipeline.estimator);
    c.can = top.raw("can");
    c.pipeline.vehicle.wheel_torque_input = maps_wheel_torque(c.can);
    c.lcm = top.raw("lcm");
    c.daemon = top.raw("daemon");
    top.reject_unknown_keys();
    const std::string invalid = c.pipeline.validate();
    if (!invalid.empty()) {
      out.error = located(invalid, root, file);
      return out;
    }
    out.config = std::move(c);
  } catch (const ConfigError& e) {
    out.error = e.what();
  } catch (const YAML::Exception& e) {
    out.error = file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
  }
  return out;
}

/// Counts where documents start, and nothing else.
class DocumentStarts : public YAML::EventHandler {
 public:
  int line = 0;  ///< 1-based
  void OnDocumentStart(const YAML::Mark& mark) override { line = mark.line + 1; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

/// The line of the text's second YAML document, 0 when it holds at most one. Parses at most two
/// documents: yaml-cpp's LoadAll, asked for all of them, never ends on some texts (the fuzzer
/// found one that filled 2 GB with empty documents).
int second_document_line(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts first;
  if (!parser.HandleNextDocument(first)) return 0;
  DocumentStarts second;
  return parser.HandleNextDocument(second) ? std::max(second.line, 1) : 0;
}

ConfigLoad failed(const std::string& error) {
  ConfigLoad out;
  out.error = error;
  return out;
}

/// The one YAML document of a config: a second one (after `---`, or anything after `...`) would
/// be read by nobody, so it is an error; so is a NUL byte, which is no YAML text.
ConfigLoad parse_text(const std::string& text, const std::string& file,
                      const std::string& directory) {
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto line = std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n') + 1;
    return failed(file + ":" + std::to_string(line) + ": a NUL byte: not a YAML config");
  }
  try {
    if (const int line = second_document_line(text); line > 0) {
      return failed(file + ":" + std::to_string(line) +
                    ": a second YAML document: a config is one (nothing after '---' or '...')");
    }
    return parse(YAML::Load(text), file, directory);
  } catch (const YAML::Exception& e) {
    return failed(file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace

std::string Config::resolve_path(const std::string& path) const {
  if (path.empty() || path.front() == '/' || directory.empty()) return path;
  return directory + "/" + path;
}

ConfigLoad load_config(const std::string& path) {
  const io::FileText text = io::read_regular_file(path, io::kMaxConfigBytes, "config");
  if (!text.ok()) {
    ConfigLoad out;
    out.error = text.error;
    return out;
  }
  if (text.text.find_first_not_of(" \t\r\n") == std::string::npos) {
    ConfigLoad out;
    out.error = path + ": empty file: expected a vmass config (docs/formats.md)";
    return out;
  }
  const auto slash = path.find_last_of('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash);
  return parse_text(text.text, path, directory);
}

ConfigLoad load_config_text(const std::string& text, const std::string& name) {
  return parse_text(text, name, "");
}

}  // namespace vmass
