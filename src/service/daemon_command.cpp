#include "daemon_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <spdlog/spdlog.h>
#include <vmass/command_t.hpp>

#include "daemon_threads.hpp"
#include "vmass/service/lcm_publisher.hpp"

namespace vmass::service::daemon {
namespace {

constexpr int kHandleTimeoutMs = 100;  // how soon the thread sees a stop

void set_text(char* out, std::size_t size, const std::string& text) {
  std::snprintf(out, size, "%s", text.c_str());
}

/// The command as the estimator thread will apply it; kRefused with why when it is not one.
DaemonCommand checked(const vmass::command_t& msg) {
  DaemonCommand c;
  c.utime = msg.utime;
  auto refuse = [&](const std::string& why) {
    c.kind = DaemonCommand::Kind::kRefused;
    set_text(c.refusal, sizeof c.refusal, why);
    return c;
  };
  if (msg.schema_version != kLcmSchemaVersion) {
    return refuse("schema_version " + std::to_string(msg.schema_version) + ", this vmassd reads " +
                  std::to_string(kLcmSchemaVersion));
  }
  if (msg.command == "reset_learnt") {
    c.kind = DaemonCommand::Kind::kResetLearnt;
    return c;
  }
  if (msg.command == "tyres_changed") {
    c.kind = DaemonCommand::Kind::kTyresChanged;
    return c;
  }
  if (msg.command != "known_mass") {
    return refuse("unknown command '" + msg.command.substr(0, 40) +
                  "' (known_mass, reset_learnt, tyres_changed)");
  }
  if (!(std::isfinite(msg.mass_kg) && msg.mass_kg > 0.0) ||
      !(std::isfinite(msg.mass_std_kg) && msg.mass_std_kg > 0.0)) {
    return refuse("known_mass needs mass_kg > 0 and mass_std_kg > 0");
  }
  c.kind = DaemonCommand::Kind::kKnownMass;
  c.mass_kg = msg.mass_kg;
  c.std_kg = msg.mass_std_kg;
  return c;
}

class CommandHandler {
 public:
  explicit CommandHandler(Shared& shared) : shared_(shared) {}
  void on_command(const lcm::ReceiveBuffer* /*rbuf*/, const std::string& channel,
                  const vmass::command_t* msg) {
    shared_.commands_received.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("{}: command {} {:.1f} kg (std {:.1f} kg) id {}{}{}", channel, msg->command,
                 msg->mass_kg, msg->mass_std_kg, msg->utime, msg->note.empty() ? "" : ": ",
                 msg->note.substr(0, 200));
    if (!shared_.commands.push(checked(*msg))) {
      spdlog::warn("{}: command id {} refused: commands are coming faster than ticks", channel,
                   msg->utime);
    }
  }

 private:
  Shared& shared_;
};

std::string kg(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string apply(const DaemonCommand& c, runtime::TickStep& step) {
  switch (c.kind) {
    case DaemonCommand::Kind::kRefused:
      return std::string("refused: ") + c.refusal;
    case DaemonCommand::Kind::kResetLearnt:
      step.reset_learnt();
      return "accepted: what was learnt about the car is forgotten (back to the config's "
             "datasheet values)";
    case DaemonCommand::Kind::kTyresChanged:
      step.tyres_changed();
      return "accepted: new tyres - the learnt scale widens by the rolling radius's uncertainty "
             "until a known mass or the standstill readings teach it again";
    case DaemonCommand::Kind::kKnownMass:
      if (!step.declare_known_mass(c.mass_kg, c.std_kg)) {
        return "refused: known mass " + kg(c.mass_kg) +
               " kg is outside the config's plausible band (empty mass to the maximum "
               "permissible mass)";
      }
      return "accepted: known mass " + kg(c.mass_kg) + " kg (std " + kg(c.std_kg) +
             " kg) from the next tick";
  }
  return "refused: unknown command";
}

}  // namespace

void command_thread(lcm::LCM& lcm, const std::string& channel, Shared& shared) {
  CommandHandler handler(shared);
  lcm::Subscription* subscription = lcm.subscribe(channel, &CommandHandler::on_command, &handler);
  while (!shared.stop_publisher.load(std::memory_order_acquire)) {
    // A provider without a connection (tcpq's server down) has no descriptor, and liblcm's
    // handle would pass -1 to select(): wait for it to reconnect instead.
    if (lcm.getFileno() < 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(kHandleTimeoutMs));
      continue;
    }
    if (lcm.handleTimeout(kHandleTimeoutMs) < 0) {
      spdlog::warn("{}: receiving commands failed; commands are not read any more", channel);
      break;
    }
  }
  lcm.unsubscribe(subscription);
}

void apply_commands(runtime::TickStep& step, Shared& shared) {
  DaemonCommand command;
  while (shared.commands.pop(&command)) {
    CommandResult result;
    result.utime = command.utime;
    set_text(result.text, sizeof result.text, apply(command, step));
    shared.command_result.write(result);
  }
}

}  // namespace vmass::service::daemon
