// vmass-replay: drive the estimation pipeline offline over recorded samples, at the configured
// tick rate, and report how it did.
//
//   vmass-replay --config FILE --samples CSV [--truth CSV] [--estimator rls|bayes]
//                [--out CSV] [--plot PNG] [--json]
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/replay/estimate_csv.hpp"
#include "vmass/replay/replay_summary.hpp"
#include "vmass/replay/samples_csv.hpp"
#include "vmass/replay/tick_resampler.hpp"

namespace fs = std::filesystem;

namespace {

// The plotting script ships beside our executables (build/bin or the install's bin).
std::string sibling_program(const std::string& name) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path candidate = self.parent_path() / name;
    if (fs::exists(candidate)) return candidate.string();
  }
  return name;  // rely on PATH
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vmass-replay: run the mass estimator offline over recorded samples"};
  std::string config_path, samples_path, truth_path, out_path, plot_path, estimator;
  bool json = false;
  app.add_option("--config", config_path, "vmass YAML config")->required();
  app.add_option("--samples", samples_path, "samples CSV (docs/formats.md)")->required();
  app.add_option("--truth", truth_path,
                 "truth CSV (time_s,mass_kg); default: truth.csv beside the samples, if any");
  app.add_option("--estimator", estimator, "override estimator.type")
      ->check(CLI::IsMember({"rls", "bayes"}));
  app.add_option("--out", out_path, "write the estimate at every tick as CSV");
  app.add_option("--plot", plot_path, "write a PNG plot (needs --out or uses a temporary CSV)");
  app.add_flag("--json", json, "print the summary as one JSON object instead of a table");
  CLI11_PARSE(app, argc, argv);

  vmass::ConfigLoad loaded = vmass::load_config(config_path);
  if (!loaded.ok()) {
    std::cerr << "vmass-replay: " << loaded.error << "\n";
    return 2;
  }
  vmass::PipelineParams params = loaded.config->pipeline;
  if (!estimator.empty()) {
    params.estimator.type =
        estimator == "rls" ? vmass::RegressorType::kRls : vmass::RegressorType::kBayes;
  }

  vmass::SamplesCsvReader reader(samples_path);
  if (!reader.error().empty()) {
    std::cerr << "vmass-replay: " << reader.error() << "\n";
    return 2;
  }
  if (truth_path.empty()) {
    const fs::path beside = fs::path(samples_path).parent_path() / "truth.csv";
    if (fs::exists(beside)) truth_path = beside.string();
  }
  std::optional<vmass::Truth> truth;
  if (!truth_path.empty()) {
    std::string error;
    truth = vmass::Truth::load(truth_path, &error);
    if (!truth) {
      std::cerr << "vmass-replay: " << error << "\n";
      return 2;
    }
  }

  std::string csv_path = out_path;
  if (csv_path.empty() && !plot_path.empty()) {
    csv_path = (fs::temp_directory_path() / ("vmass-replay-" + std::to_string(::getpid()) +
                                             ".csv")).string();
  }
  std::unique_ptr<vmass::EstimateCsvWriter> writer;
  if (!csv_path.empty()) {
    writer = std::make_unique<vmass::EstimateCsvWriter>(csv_path);
    if (!writer->ok()) {
      std::cerr << "vmass-replay: " << csv_path << ": cannot write\n";
      return 2;
    }
  }

  auto pipeline = std::make_unique<vmass::Pipeline>(params);
  vmass::ReplaySummary summary(truth);
  // A held sample older than 5 ticks is stale (a gap in the recording).
  vmass::TickResampler ticks(params.estimator.differencing.tick_rate_hz,
                             5.0 / params.estimator.differencing.tick_rate_hz);
  auto on_tick = [&](const vmass::Sample& sample) {
    pipeline->step(sample);
    summary.add(pipeline->estimate());
    if (writer) writer->write(pipeline->estimate());
  };
  while (auto sample = reader.next()) ticks.push(*sample, on_tick);

  for (const auto& w : reader.warnings()) std::cerr << "vmass-replay: warning: " << w << "\n";
  if (reader.skipped_rows() > 0) {
    std::cerr << "vmass-replay: skipped " << reader.skipped_rows() << " malformed rows\n";
  }
  if (writer && !writer->close()) {
    std::cerr << "vmass-replay: " << csv_path << ": write failed\n";
    return 1;
  }
  const std::string name(pipeline->regressor().name());
  std::cout << (json ? summary.json(name) + "\n" : summary.table(name));

  if (!plot_path.empty()) {
    std::string command = shell_quote(sibling_program("vmass-plot")) + " --estimates " +
                          shell_quote(csv_path) + " --out " + shell_quote(plot_path) +
                          " --title " + shell_quote("vmass-replay " + name + ": " + samples_path);
    if (!truth_path.empty()) command += " --truth " + shell_quote(truth_path);
    const int rc = std::system(command.c_str());
    if (out_path.empty()) fs::remove(csv_path);
    if (rc != 0) {
      std::cerr << "vmass-replay: plotting failed (" << command << ")\n";
      return 1;
    }
    if (!json) std::cout << "plot                 " << plot_path << "\n";
  }
  return 0;
}
