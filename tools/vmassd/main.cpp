// vmassd: the real-time vehicle mass estimation daemon. Only the command line is here: the
// daemon is vmass::service::run_daemon (vmass/service/daemon.hpp: its threads and how it ticks).
//
//   vmassd --config FILE [--can IFACE | --can-fd FD | --replay LOG [--interface NAME]
//          [--speed X|max] | --samples CSV [--speed X|max]] [--lcm-url URL] [--state-file PATH]
//          [--no-restore]
//
// Publishes vmass.mass_estimate_t on VMASS_ESTIMATE, vmass.status_t on VMASS_STATUS (and
// vmass.pair_t on VMASS_PAIRS when lcm.publish_pairs). Runs under systemd as Type=notify
// (config/vmassd.service). SIGTERM/SIGINT: final status, state saved, exit 0. A recording
// (--replay, --samples) stops the daemon at its end. Exit codes (tools/common/exit_code.hpp):
// 0 orderly stop, 1 start-up failure (input or LCM cannot be opened), 2 usage or config error
// (or a replay without a frame on its --interface).
#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "interface_option.hpp"
#include "vmass/service/daemon.hpp"
#include "vmass/service/journal_logging.hpp"
#include "vmass/service/stop_signals.hpp"

int main(int argc, char** argv) {
  // SIGTERM is handled from here on: during start-up it ends the process at once (exit 0).
  vmass::service::install_stop_signals();
  CLI::App app{"vmassd: live vehicle mass estimation from CAN data, published on LCM"};
  vmass::service::DaemonOptions o;
  app.add_option("--config", o.config_path, "vmass YAML config")->required();
  auto* can = app.add_option("--can", o.can_interface,
                             "SocketCAN interface (default: daemon.can_interface, can0)");
  auto* can_fd = app.add_option("--can-fd", o.can_fd,
                                "read SocketCAN records (struct can_frame/canfd_frame) from this "
                                "inherited descriptor instead of an interface (benchmarks, tests)")
                     ->check(CLI::NonNegativeNumber);
  auto* replay = app.add_option(
      "--replay", o.replay_log,
      "replay a CAN log (candump -l, Vector ASC/BLF, PEAK TRC, ASAM MDF4; found from its content)");
  vmass::tools::add_interface_option(app, &o.replay_interface)->needs(replay);
  auto* samples = app.add_option("--samples", o.samples_csv,
                                 "replay a samples.csv (inputs already in SI units)");
  app.add_option("--speed", o.speed,
                 "recordings: playback speed factor, or 'max' (ticks follow log time)")
      ->default_str("1");
  app.add_option("--lcm-url", o.lcm_url, "LCM URL (overrides lcm.url)");
  app.add_option("--state-file", o.state_file,
                 "saved-state file (overrides daemon.state_file / $STATE_DIRECTORY)");
  app.add_flag("--no-restore", o.no_restore, "do not restore the saved state at start");
  can->excludes(replay)->excludes(samples)->excludes(can_fd);
  can_fd->excludes(replay)->excludes(samples);
  replay->excludes(samples);
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;

  // Diagnostics go to stderr (the journal under systemd, in its form); stdout stays free.
  vmass::service::setup_logging("vmassd");
  return vmass::service::run_daemon(o);
}
