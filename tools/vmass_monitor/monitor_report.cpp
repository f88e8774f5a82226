#include "monitor_report.hpp"

#include <cstdarg>
#include <cstdio>

namespace vmass::monitor {
namespace {

constexpr std::size_t kLabelWidth = 10;
constexpr std::string_view kGap = "   ";

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buf[256];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

/// An item no wider than `room`: long ones keep their start and end around "...".
std::string fit(const std::string& item, std::size_t room) {
  if (item.size() <= room || room < 8) return item;
  const std::size_t head = (room - 3) / 2;
  return item.substr(0, head) + "..." + item.substr(item.size() - (room - 3 - head));
}

long long ll(std::int64_t v) { return static_cast<long long>(v); }

std::vector<std::string> estimate_items(const vmass::mass_estimate_t& e) {
  if (!e.mass_known) return {"(not known yet)"};
  return {format("%.1f kg", e.mass_kg),
          format("95%% [%.1f, %.1f] kg", e.mass_ci_low_kg, e.mass_ci_high_kg),
          format("std %.1f kg", e.mass_std_kg), format("mu %.1f N", e.mu_n)};
}

std::string estimate_lines(const vmass::mass_estimate_t& e) {
  std::string out = wrap_items("mass", estimate_items(e));
  out +=
      wrap_items("status", {e.status_name + " (" + e.reason_name + ")", "estimator " + e.estimator,
                            format("initial %.1f kg", e.initial_mass_kg),
                            format("pairs %lld", ll(e.pairs_used)),
                            format("t %.2f s", static_cast<double>(e.utime) * 1e-6)});
  out += wrap_items("available", {format("longitudinal %.1f %% (%lld pairs, %lld rejected)",
                                         100.0 * e.longitudinal_availability,
                                         ll(e.longitudinal_accepted), ll(e.longitudinal_rejected)),
                                  format("lateral %.1f %% (%lld pairs, %lld rejected)",
                                         100.0 * e.lateral_availability, ll(e.lateral_accepted),
                                         ll(e.lateral_rejected))});
  return out;
}

std::vector<std::string> input_items(const vmass::status_t& s) {
  std::vector<std::string> items;
  for (int i = 0; i < s.num_inputs; ++i) {
    const auto k = static_cast<std::size_t>(i);
    items.push_back(s.input_age_s[k] < 0.0
                        ? s.input_name[k] + " never"
                        : format("%s %s %.0f ms", s.input_name[k].c_str(),
                                 s.input_valid[k] ? "ok" : "INVALID", s.input_age_s[k] * 1e3));
  }
  return items;
}

std::string status_lines(const vmass::status_t& s) {
  std::vector<std::string> daemon = {s.state_name, format("up %.0f s", s.uptime_s),
                                     "version " + s.version, "input " + s.source};
  if (!s.detail.empty()) daemon.push_back(s.detail);
  std::string out = wrap_items("daemon", daemon);
  out += wrap_items("ticks", {format("%lld at %.0f Hz", ll(s.ticks), s.tick_rate_hz),
                              format("overruns %lld", ll(s.tick_overruns)),
                              format("skipped %lld", ll(s.ticks_skipped)),
                              format("queue drops %lld", ll(s.publish_queue_drops)),
                              format("jitter p50/p99/max %.0f/%.0f/%.0f us", s.jitter_p50_us,
                                     s.jitter_p99_us, s.jitter_max_us)});
  out += wrap_items(
      "frames",
      {format("%lld received", ll(s.frames_received)), format("%lld decoded", ll(s.frames_decoded)),
       format("%lld unknown", ll(s.frames_unknown)),
       format("%lld malformed", ll(s.frames_malformed)),
       format("%lld dropped", ll(s.frames_dropped)), format("%lld bus errors", ll(s.bus_errors)),
       format("%lld reopens", ll(s.source_reopens))});
  return out + wrap_items("inputs", input_items(s));
}

}  // namespace

std::string wrap_items(std::string_view label, const std::vector<std::string>& items,
                       std::size_t width) {
  std::string out(label);
  out.resize(std::max(out.size() + 1, kLabelWidth), ' ');
  std::size_t column = out.size();
  bool first_on_line = true;
  for (const std::string& raw : items) {
    const std::string item = fit(raw, width - kLabelWidth);
    if (!first_on_line && column + kGap.size() + item.size() > width) {
      out += "\n" + std::string(kLabelWidth, ' ');
      column = kLabelWidth;
      first_on_line = true;
    }
    if (!first_on_line) out += kGap;
    out += item;
    column += (first_on_line ? 0 : kGap.size()) + item.size();
    first_on_line = false;
  }
  return out + "\n";
}

std::string silence_message(const Silence& silence) {
  if (silence.limit_s <= 0.0 || silence.estimate_s <= silence.limit_s) return "";
  std::string out = format("no estimate for %.0f s: is vmassd running?", silence.estimate_s);
  if (silence.status_s >= 0.0) out += format(" (last status %.0f s ago)", silence.status_s);
  return out;
}

std::string monitor_report(const std::string& url, double estimate_hz, double status_hz,
                           const vmass::mass_estimate_t* estimate, const vmass::status_t* status,
                           const Silence& silence) {
  std::string out = wrap_items("vmass-monitor", {url, format("estimates %.1f Hz", estimate_hz),
                                                 format("status %.2f Hz", status_hz)});
  if (const std::string message = silence_message(silence); !message.empty()) {
    out += wrap_items("SILENT", {message});
  }
  out += estimate ? estimate_lines(*estimate) : wrap_items("mass", {"(no estimate received)"});
  out += status ? status_lines(*status) : wrap_items("daemon", {"(no status received)"});
  return out;
}

}  // namespace vmass::monitor
