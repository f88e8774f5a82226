// vmass-ctl: tells a running vmassd what only its user knows, over LCM, and prints its answer.
//
//   vmass-ctl [--config FILE] [--lcm-url URL] [--timeout S] known-mass KG [--std KG] [--note TEXT]
//   vmass-ctl [--config FILE] [--lcm-url URL] [--timeout S] reset-learnt [--note TEXT]
//   vmass-ctl [--config FILE] [--lcm-url URL] [--timeout S] tyres-changed [--note TEXT]
//
//   known-mass KG   the current load's mass is KG (a weighbridge ticket, "empty, driver only"),
//                   with a std of --std kg (default 0.5 % of KG)
//   reset-learnt    forget what vmassd learnt about the car (back to the config's datasheet)
//   tyres-changed   new tyres were fitted: the learnt scale widens by the rolling radius's
//                   uncertainty, the rest of what was learnt is kept; a declared known mass
//                   ends (send it before a weighbridge ticket of the same visit)
//
// It publishes one vmass.command_t (utime: CLOCK_REALTIME, its id) on the config's
// lcm.command_channel and waits up to --timeout seconds (default 3) for a vmass.status_t on
// lcm.status_channel whose last_command_utime is that id, then prints the daemon's
// last_command_result ("vmassd: accepted: known mass 1650.0 kg (std 8.2 kg) from the next
// tick"). Exit 0 when vmassd accepted it, 1 when it refused it, when no answer came or LCM
// cannot be opened, 2 on a usage or config error (tools/common/exit_code.hpp).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <vmass/command_t.hpp>
#include <vmass/status_t.hpp>

#include "config_lcm_settings.hpp"
#include "exit_code.hpp"
#include "subcommands_formatter.hpp"
#include "vmass/config/config.hpp"
#include "vmass/service/lcm_publisher.hpp"
#include "vmass/service/lcm_url.hpp"
#include "vmass/service/service_config.hpp"

namespace {

constexpr double kDefaultRelativeStd = 0.005;  // --std: 0.5 % of KG

/// A number that is finite and above 0; CLI11 names the option in front of the message
/// ("--std: expected a finite number > 0 (kg), got '0'").
CLI::Validator positive_finite(const std::string& unit) {
  return CLI::Validator(
      [unit](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(v) || !(v > 0.0)) {
          return "expected a finite number > 0 (" + unit + "), got '" + text + "'";
        }
        return "";
      },
      "> 0");
}

struct Options {
  std::string config_path, url, note;
  std::string command;  ///< "known_mass", "reset_learnt" or "tyres_changed"
  double mass_kg = 0.0;
  double std_kg = 0.0;  ///< 0: kDefaultRelativeStd of mass_kg
  double timeout_s = 3.0;
};

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{
      "vmass-ctl: tell a running vmassd a known mass of the current load, that new tyres were "
      "fitted, or to forget what it learnt about the car; prints its answer"};
  app.require_subcommand(1);
  app.fallthrough();  // the global options after the subcommand too
  app.formatter(std::make_shared<vmass::tools::SubcommandsFormatter>());
  app.set_help_all_flag("--help-all", "print this help with every subcommand's options, then exit");
  app.add_option("--config", o->config_path,
                 "vmassd's config (for its lcm: URL, command and status channels)");
  app.add_option("--lcm-url", o->url,
                 "LCM URL (default: the config's lcm.url, else vmassd's default "
                 "udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--timeout", o->timeout_s, "seconds to wait for vmassd's answer (default 3)")
      ->check(positive_finite("s"));

  CLI::App* known = app.add_subcommand(
      "known-mass",
      "the current load's mass is KG (a weighbridge ticket): vmassd publishes it "
      "and learns the car's scale from the drive on it");
  known->add_option("KG", o->mass_kg, "the load's mass, kg")
      ->required()
      ->check(positive_finite("kg"));
  known->add_option("--std", o->std_kg, "its standard deviation, kg (default 0.5 % of KG)")
      ->check(positive_finite("kg"));
  known->add_option("--note", o->note, "a note for vmassd's journal, e.g. \"weighbridge 4711\"");

  CLI::App* reset =
      app.add_subcommand("reset-learnt",
                         "forget what vmassd learnt about the car (another car, a retrofit): back "
                         "to the config's datasheet values");
  reset->add_option("--note", o->note, "a note for vmassd's journal");

  CLI::App* tyres = app.add_subcommand(
      "tyres-changed",
      "new tyres were fitted: the learnt scale widens by the rolling radius's uncertainty "
      "(estimator.learning.tyre_change_std_fraction); the rest of what was learnt is kept. It "
      "ends a declared known mass: send it before a weighbridge ticket of the same visit");
  tyres->add_option("--note", o->note, "a note for vmassd's journal, e.g. \"315/80 R22.5 new\"");

  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return code;
  o->command = known->parsed() ? "known_mass" : tyres->parsed() ? "tyres_changed" : "reset_learnt";
  if (known->parsed() && o->std_kg <= 0.0) o->std_kg = kDefaultRelativeStd * o->mass_kg;
  return std::nullopt;
}

/// The LCM URL and channels: the config's lcm: section, then --lcm-url. False on an error
/// (said on stderr).
bool lcm_settings_for(const Options& o, vmass::service::LcmSettings* out) {
  if (!vmass::tools::load_lcm_settings(o.config_path, "vmass-ctl", out)) return false;
  if (!o.url.empty()) {
    if (const std::string e = vmass::service::lcm_url_error(o.url); !e.empty()) {
      std::fprintf(stderr, "vmass-ctl: --lcm-url: %s\n", e.c_str());
      return false;
    }
    out->url = o.url;
  }
  return true;
}

std::int64_t realtime_us() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

/// Listens for the status that answers the command with id `utime`.
class AnswerWait {
 public:
  explicit AnswerWait(std::int64_t utime) : utime_(utime) {}
  void on_status(const lcm::ReceiveBuffer*, const std::string&, const vmass::status_t* msg) {
    ++statuses_;
    version_ = msg->version;
    if (msg->last_command_utime == utime_ && !answer_) answer_ = msg->last_command_result;
  }
  const std::optional<std::string>& answer() const { return answer_; }
  long statuses() const { return statuses_; }
  const std::string& version() const { return version_; }

 private:
  std::int64_t utime_;
  std::optional<std::string> answer_;
  long statuses_ = 0;
  std::string version_;
};

/// Handles LCM until the answer came or `timeout_s` passed.
void wait_for_answer(lcm::LCM& lcm, const AnswerWait& wait, double timeout_s) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                        std::chrono::duration<double>(timeout_s));
  while (!wait.answer()) {
    const auto left_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left_ms <= 0) break;
    if (lcm.handleTimeout(static_cast<int>(std::min<long long>(left_ms, 100))) < 0) break;
  }
}

/// Why no answer came: nothing on the status channel (no vmassd there), or statuses that do not
/// answer (a vmassd that does not read this command channel).
void say_no_answer(const AnswerWait& wait, const Options& o,
                   const vmass::service::LcmSettings& settings) {
  std::fprintf(stderr, "vmass-ctl: no answer from vmassd within %g s: ", o.timeout_s);
  if (wait.statuses() == 0) {
    std::fprintf(stderr, "is it running on %s?\n", settings.url.c_str());
  } else {
    std::fprintf(stderr,
                 "vmassd %s publishes its status on %s but did not answer the command sent on "
                 "%s (its lcm.command_channel?)\n",
                 wait.version().c_str(), settings.status_channel.c_str(),
                 settings.command_channel.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse_options(argc, argv, &o)) return *code;
  vmass::service::LcmSettings settings;
  if (!lcm_settings_for(o, &settings)) return vmass::tools::kExitUsage;
  lcm::LCM lcm(settings.url);
  if (!lcm.good()) {
    std::fprintf(stderr, "vmass-ctl: cannot open LCM at '%s'\n", settings.url.c_str());
    return vmass::tools::kExitFailure;
  }
  vmass::command_t command{};
  command.utime = realtime_us();
  command.schema_version = vmass::service::kLcmSchemaVersion;  // the one vmassd reads
  command.command = o.command;
  command.mass_kg = o.mass_kg;
  command.mass_std_kg = o.std_kg;
  command.note = o.note;
  AnswerWait wait(command.utime);
  // Subscribed before the command leaves, so that a quick answer is not missed.
  lcm.subscribe(settings.status_channel, &AnswerWait::on_status, &wait);
  if (lcm.publish(settings.command_channel, &command) != 0) {
    std::fprintf(stderr, "vmass-ctl: cannot publish on %s at '%s'\n",
                 settings.command_channel.c_str(), settings.url.c_str());
    return vmass::tools::kExitFailure;
  }
  wait_for_answer(lcm, wait, o.timeout_s);
  if (!wait.answer()) {
    say_no_answer(wait, o, settings);
    return vmass::tools::kExitFailure;
  }
  std::printf("vmassd: %s\n", wait.answer()->c_str());
  return wait.answer()->rfind("accepted", 0) == 0 ? vmass::tools::kExitOk
                                                  : vmass::tools::kExitFailure;
}
