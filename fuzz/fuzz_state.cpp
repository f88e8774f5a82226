// libFuzzer target: the daemon's state-file reader (parse_state), then, for a state that
// parses, the plausibility check the daemon runs before restoring and Pipeline::restore, with
// the parameters of config/vmassd.example.yaml (both regressor types).
// A state file ends in a checksum line, which a mutated input almost never matches; so each
// input is tried as it is and also with its last checksum line (if any) replaced by a correct
// one (FNV-1a 64, as state_store.cpp computes it), so that the fields behind the check are
// reached.
#include <cinttypes>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/service/state_plausibility.hpp"
#include "vmass/service/state_store.hpp"

#ifndef VMASS_SOURCE_DIR
#error "VMASS_SOURCE_DIR: the source tree, for config/vmassd.example.yaml"
#endif

namespace {

std::vector<vmass::PipelineParams>* g_params = nullptr;

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

void parse_and_restore(const std::string& text) {
  vmass::service::SavedState state;
  std::string error;
  if (!vmass::service::parse_state(text, &state, &error)) return;
  for (const vmass::PipelineParams& params : *g_params) {
    if (!vmass::service::implausible_state(state.snapshot, params).empty()) continue;
    vmass::Pipeline pipeline(params);
    (void)pipeline.restore(state.snapshot);
    (void)pipeline.snapshot();
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const std::string path = std::string(VMASS_SOURCE_DIR) + "/config/vmassd.example.yaml";
  const vmass::ConfigLoad load = vmass::load_config(path);
  if (!load.ok()) {
    std::fprintf(stderr, "fuzz_state: %s\n", load.error.c_str());
    std::abort();
  }
  g_params = new std::vector<vmass::PipelineParams>();
  for (const vmass::RegressorType type :
       {vmass::RegressorType::kRls, vmass::RegressorType::kBayes}) {
    vmass::PipelineParams params = load.config->pipeline;
    params.estimator.type = type;
    if (!params.validate().empty()) {
      std::fprintf(stderr, "fuzz_state: %s\n", params.validate().c_str());
      std::abort();
    }
    g_params->push_back(params);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  parse_and_restore(text);
  const std::size_t checksum_at = text.rfind("checksum ");
  if (checksum_at != std::string::npos && (checksum_at == 0 || text[checksum_at - 1] == '\n')) {
    text.resize(checksum_at);
  }
  if (!text.empty() && text.back() != '\n') text += '\n';
  char line[40];
  std::snprintf(line, sizeof line, "checksum %016" PRIx64 "\n", fnv1a(text));
  parse_and_restore(text + line);
  return 0;
}
