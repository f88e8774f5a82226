// Config: the one YAML file that configures vmass (see docs/formats.md for every key).
//
// load_config() reads and validates the vehicle, suspension and estimator sections into
// PipelineParams; the `can` and `lcm` sections are kept as raw YAML for the layers that own them.
// Every error names the file, the line and the key; unknown keys are errors.
// Configuration time only; not thread-safe.
#pragma once

#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "vmass/core/pipeline.hpp"

namespace vmass {

struct Config {
  std::string file;       ///< path it was read from ("<string>" for in-memory text)
  std::string directory;  ///< for paths relative to the config file
  PipelineParams pipeline;
  YAML::Node can;     ///< raw `can:` section (may be null)
  YAML::Node lcm;     ///< raw `lcm:` section (may be null)
  YAML::Node daemon;  ///< raw `daemon:` section (may be null)

  /// A path from the config, resolved against the config file's directory.
  std::string resolve_path(const std::string& path) const;
};

struct ConfigLoad {
  std::optional<Config> config;
  std::string error;  ///< "file:line: key: message" when config is empty
  bool ok() const { return config.has_value(); }
};

ConfigLoad load_config(const std::string& path);
ConfigLoad load_config_text(const std::string& text, const std::string& name = "<string>");

}  // namespace vmass
