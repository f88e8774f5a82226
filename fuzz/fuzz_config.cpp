// libFuzzer target: the config loader (load_config_text: YAML, then every section's checks),
// and for a config that loads, its `can:` section's inputs, e2e and plausibility against the
// demo vehicle's DBC (the parts of load_can_inputs that do not read files). Errors are results;
// nothing may throw out of the loaders.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "vmass/can/decoder.hpp"
#include "vmass/config/config.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/signals/message_protection.hpp"
#include "vmass/signals/plausibility_params.hpp"
#include "vmass/signals/signal_mapping.hpp"

#ifndef VMASS_SOURCE_DIR
#error "VMASS_SOURCE_DIR: the source tree, for its DBC files (set by fuzz/CMakeLists.txt)"
#endif

namespace {

const vmass::can::Decoder* g_decoder = nullptr;

void check_can_section(const vmass::Config& config) {
  if (!config.can || !config.can.IsMap()) return;
  // As load_can_inputs takes the nodes (raw() never returns a yaml-cpp "zombie" node).
  vmass::YamlReader can(config.can, config.file, "can");
  vmass::signals::SignalMapping mapping;
  std::string error = vmass::signals::parse_signal_mapping(
      can.raw("inputs"), config.file, *g_decoder, "demo_vehicle.dbc", &mapping);
  if (error.empty()) {
    error = vmass::signals::parse_message_protection(can.raw("e2e"), config.file, *g_decoder,
                                                     "demo_vehicle.dbc", &mapping.protection);
  }
  if (error.empty()) {
    error = vmass::signals::parse_plausibility(can.raw("plausibility"), config.file,
                                               &mapping.plausibility);
  }
  if (error.empty()) (void)mapping.describe();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const std::string path = std::string(VMASS_SOURCE_DIR) + "/config/demo_vehicle.dbc";
  vmass::can::DbcParseResult parsed = vmass::can::load_dbc_file(path);
  auto decoder = vmass::can::Decoder::compile(std::move(parsed.database));
  if (!parsed.ok() || !decoder) {
    std::fprintf(stderr, "fuzz_config: %s: cannot load\n", path.c_str());
    std::abort();
  }
  g_decoder = new vmass::can::Decoder(std::move(*decoder));
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const vmass::ConfigLoad load = vmass::load_config_text(text, "fuzz.yaml");
  if (load.ok()) check_can_section(*load.config);
  return 0;
}
