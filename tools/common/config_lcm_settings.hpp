// The LCM URL and channels of a config's `lcm:` section, for the tools that talk to a running
// vmassd (vmass-monitor, vmass-ctl): the same loader and the same located errors as vmassd.
#pragma once

#include <cstdio>
#include <string>

#include "vmass/config/config.hpp"
#include "vmass/service/service_config.hpp"

namespace vmass::tools {

/// `*out` from the config at `path` (kept as it is when `path` is ""). False, with the error
/// on stderr after "`tool`: ", when the config or its lcm: section is not valid.
inline bool load_lcm_settings(const std::string& path, const char* tool,
                              service::LcmSettings* out) {
  if (path.empty()) return true;
  const ConfigLoad loaded = load_config(path);
  if (!loaded.ok()) {
    std::fprintf(stderr, "%s: %s\n", tool, loaded.error.c_str());
    return false;
  }
  const auto settings = service::load_service_settings(*loaded.config);
  if (!settings.ok()) {
    std::fprintf(stderr, "%s: %s\n", tool, settings.error.c_str());
    return false;
  }
  *out = settings.settings.lcm;
  return true;
}

}  // namespace vmass::tools
