#include "vmass/service/service_config.hpp"

#include <cmath>

#include "vmass/config/yaml_reader.hpp"
#include "vmass/service/lcm_url.hpp"

namespace vmass::service {
namespace {

bool valid_channel(const std::string& name) {
  if (name.empty() || name.size() > 63) return false;
  for (char c : name) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.' || c == '-' || c == '/';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

std::string LcmSettings::validate() const {
  if (url.empty()) return "lcm.url: must not be empty";
  if (const std::string e = lcm_url_error(url); !e.empty()) return "lcm.url: " + e;
  if (!valid_channel(estimate_channel)) return "lcm.estimate_channel: invalid channel name";
  if (!valid_channel(status_channel)) return "lcm.status_channel: invalid channel name";
  if (!valid_channel(pairs_channel)) return "lcm.pairs_channel: invalid channel name";
  if (!valid_channel(command_channel)) return "lcm.command_channel: invalid channel name";
  if (estimate_decimation < 1) return "lcm.estimate_decimation: must be >= 1";
  if (!(status_period_s >= 0.01 && status_period_s <= 3600.0)) {
    return "lcm.status_period_s: must be in [0.01, 3600]";
  }
  return "";
}

std::string RealtimeSettings::validate() const {
  if (priority < 0 || priority > 99) return "daemon.realtime.priority: must be in [0, 99]";
  for (int cpu : cpu_affinity) {
    if (cpu < 0 || cpu >= 1024) return "daemon.realtime.cpu_affinity: CPUs must be in [0, 1023]";
  }
  return "";
}

std::string DaemonSettings::validate() const {
  if (can_interface.empty() || can_interface.size() >= 16) {
    return "daemon.can_interface: must be 1..15 characters";
  }
  if (!(persist_interval_s >= 0.1)) return "daemon.persist_interval_s: must be >= 0.1";
  if (!(input_timeout_s >= 0.0 && std::isfinite(input_timeout_s))) {
    return "daemon.input_timeout_s: must be >= 0 (0: 5 ticks)";
  }
  if (publish_queue < 16 || publish_queue > (1 << 20)) {
    return "daemon.publish_queue: must be in [16, 1048576]";
  }
  if (!(receive_period_ms >= 0.0 && receive_period_ms <= 100.0)) {
    return "daemon.receive_period_ms: must be in [0, 100] (0: read as frames arrive)";
  }
  return realtime.validate();
}

ServiceSettingsLoad load_service_settings(const Config& config) {
  ServiceSettingsLoad out;
  ServiceSettings& s = out.settings;
  // A bound violation is reported at the key's line: re-read through the reader to fail there.
  try {
    YamlReader lcm(config.lcm, config.file, "lcm");
    read_fields(lcm, kLcmFields, &s.lcm);
    lcm.reject_unknown_keys();
    const std::string lcm_error = s.lcm.validate();
    if (!lcm_error.empty()) {
      const std::string key = lcm_error.substr(4, lcm_error.find(':') - 4);
      lcm.fail(key, lcm_error.substr(lcm_error.find(':') + 2));
    }

    YamlReader daemon(config.daemon, config.file, "daemon");
    read_fields(daemon, kDaemonFields, &s.daemon);
    YamlReader rt = daemon.child("realtime");
    read_fields(rt, kRealtimeFields, &s.daemon.realtime);
    rt.reject_unknown_keys();
    daemon.reject_unknown_keys();
    const std::string daemon_error = s.daemon.validate();
    if (!daemon_error.empty()) {
      // "daemon.realtime.priority: ..." -> fail at the innermost reader that has the key.
      const std::string full = daemon_error.substr(0, daemon_error.find(':'));
      const std::string message = daemon_error.substr(daemon_error.find(':') + 2);
      if (full.rfind("daemon.realtime.", 0) == 0) rt.fail(full.substr(16), message);
      daemon.fail(full.substr(7), message);
    }

    if (config.can && config.can.IsMap() && config.can["dbc"]) {
      YAML::Node dbc = config.can["dbc"];
      if (!dbc.IsScalar() || dbc.Scalar().empty()) {
        throw ConfigError(config.file + ":" + std::to_string(dbc.Mark().line + 1) +
                          ": can.dbc: expected a file name");
      }
      s.dbc_path = config.resolve_path(dbc.Scalar());
    }
  } catch (const ConfigError& e) {
    out.error = e.what();
  } catch (const YAML::Exception& e) {
    out.error = config.file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
  }
  return out;
}

}  // namespace vmass::service
