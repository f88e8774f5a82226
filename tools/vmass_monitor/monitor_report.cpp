#include "monitor_report.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace vmass::monitor {
namespace {

constexpr std::size_t kLabelWidth = 10;
constexpr std::size_t kVerdictsShown = 3;  // the no-pair line's verdicts, the rest summed

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

/// 17800 -> "17,800".
std::string grouped(std::int64_t v) {
  std::string digits = std::to_string(v < 0 ? -v : v);
  for (std::size_t i = digits.size(); i > 3; i -= 3) digits.insert(i - 3, ",");
  return v < 0 ? "-" + digits : digits;
}

/// A text from the network with no control character (an escape sequence, a line break) left
/// to reach the terminal: each one is a '?'.
std::string printable(std::string text) {
  for (char& c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '?';
  }
  return text;
}

/// A text from the network as its words (printable).
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(' ', start), text.size());
    if (end > start) out.push_back(printable(text.substr(start, end - start)));
    start = end + 1;
  }
  return out;
}

/// "45 s", "12 min", "3 h".
std::string age(double s) {
  if (s < 120.0) return format("%.0f s", s);
  if (s < 7200.0) return format("%.0f min", s / 60.0);
  return format("%.0f h", s / 3600.0);
}

std::vector<std::string> estimate_items(const vmass::mass_estimate_t& e) {
  if (!e.mass_known) return {"(not known yet)"};
  std::vector<std::string> items = {format("%.1f kg", e.mass_kg)};
  if (e.known_mass) items.emplace_back("known (declared)");
  for (std::string item : {format("95%% [%.1f, %.1f] kg", e.mass_ci_low_kg, e.mass_ci_high_kg),
                           format("std %.1f kg", e.mass_std_kg), format("mu %.1f N", e.mu_n)}) {
    items.push_back(std::move(item));
  }
  return items;
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

/// Each gear's learnt rotating mass, e.g. "gear 1 -1250 +- 400 kg", once a drive taught it.
void gear_items(const vmass::status_t& s, std::vector<std::string>* items) {
  if (s.num_learnt_gears <= 0) return;
  if (s.learnt_gear_drives <= 0) {
    items->emplace_back("rotating masses: datasheet (no drive with two gears yet)");
    return;
  }
  items->push_back(format("rotating masses from %lld drive%s:", ll(s.learnt_gear_drives),
                          s.learnt_gear_drives == 1 ? "" : "s"));
  const auto n =
      std::min<std::size_t>({static_cast<std::size_t>(s.num_learnt_gears),
                             s.learnt_gear_correction_kg.size(), s.learnt_gear_std_kg.size()});
  for (std::size_t i = 0; i < n; ++i) {
    items->push_back(format("gear %zu %+.0f +- %.0f kg", i + 1, s.learnt_gear_correction_kg[i],
                            s.learnt_gear_std_kg[i]));
  }
}

/// New tyres declared, and what taught the scale since: "new tyres: 0 known masses and 2
/// standstill readings since" (the readings count in the scale until a known mass).
std::string tyres_item(const vmass::status_t& s) {
  const std::string times =
      s.learnt_tyre_changes == 1 ? "" : format(" x%lld", ll(s.learnt_tyre_changes));
  std::string out =
      format("new tyres%s: %lld known mass%s", times.c_str(), ll(s.learnt_evidence_since_tyres),
             s.learnt_evidence_since_tyres == 1 ? "" : "es");
  if (s.learnt_anchors > 0) {
    out += format(" and %lld standstill reading%s", ll(s.learnt_anchors),
                  s.learnt_anchors == 1 ? "" : "s");
  }
  return out + " since";
}

/// What vmassd learnt about the car: the lumped longitudinal scale, the gears' rotating masses
/// and the changes it saw.
std::string learnt_lines(const vmass::status_t& s) {
  std::vector<std::string> items;
  if (s.learnt_evidence <= 0 && s.learnt_anchors > 0) {
    items.push_back(format(
        "scale %.3f +- %.1f %% from %lld standstill reading%s (no known mass yet)", s.learnt_scale,
        100.0 * s.learnt_scale_std, ll(s.learnt_anchors), s.learnt_anchors == 1 ? "" : "s"));
  } else if (s.learnt_evidence <= 0) {
    items.emplace_back("scale: datasheet (no known mass yet)");
  } else {
    items.push_back(format("scale %.3f +- %.1f %% from %lld drive%s on a known mass",
                           s.learnt_scale, 100.0 * s.learnt_scale_std, ll(s.learnt_evidence),
                           s.learnt_evidence == 1 ? "" : "s"));
  }
  if (s.learnt_changes > 0) {
    items.push_back(format("%lld change%s of the car detected", ll(s.learnt_changes),
                           s.learnt_changes == 1 ? "" : "s"));
  }
  if (s.learnt_tyre_changes > 0) items.push_back(tyres_item(s));
  gear_items(s, &items);
  return wrap_items("learnt", items);
}

/// The tyre watch, once it holds a launch or told a change: "12 launches and 8 stops since the
/// last change   largest step +1.8 % (3.1 std, suspected)   1 change told".
std::string tyre_watch_lines(const vmass::status_t& s) {
  if (s.tyre_watch_launches + s.tyre_watch_stops <= 0 && s.tyre_watch_changes <= 0) return "";
  std::vector<std::string> items = {
      format("%lld launch%s and %lld stop%s since the last change", ll(s.tyre_watch_launches),
             s.tyre_watch_launches == 1 ? "" : "es", ll(s.tyre_watch_stops),
             s.tyre_watch_stops == 1 ? "" : "s")};
  if (s.tyre_watch_step_sigma > 0.0) {
    items.push_back(format("largest step %+.1f %% (%.1f std%s)", 100.0 * s.tyre_watch_step,
                           s.tyre_watch_step_sigma, s.tyre_watch_suspected ? ", suspected" : ""));
  }
  if (s.tyre_watch_changes > 0) {
    items.push_back(format("%lld change%s told", ll(s.tyre_watch_changes),
                           s.tyre_watch_changes == 1 ? "" : "s"));
  }
  return wrap_items("tyres", items);
}

/// The drive's pair-term fit, while it applies: "rotating masses +12 +- 9 %   converter -5 +-
/// 10 %   mass +230 +- 180 kg   412 pairs".
std::string pair_fit_lines(const vmass::status_t& s) {
  if (!s.pair_fit_applies) return "";
  std::vector<std::string> items = {format("rotating masses %+.0f +- %.0f %%",
                                           100.0 * s.pair_fit_rotating_error,
                                           100.0 * s.pair_fit_rotating_error_std)};
  if (s.pair_fit_converter_multiplied) {
    items.push_back(format("converter %+.0f +- %.0f %%", 100.0 * s.pair_fit_converter_error,
                           100.0 * s.pair_fit_converter_error_std));
  }
  items.push_back(format("mass %+.0f +- %.0f kg", s.pair_fit_shift_kg, s.pair_fit_shift_std_kg));
  items.push_back(format("%lld pairs", ll(s.pair_fit_pairs)));
  return wrap_items("pair fit", items);
}

/// vmassd's answer to the last command (vmass-ctl) and how long ago it was sent; "" before one.
std::string command_lines(const vmass::status_t& s, std::int64_t now_utime) {
  if (s.last_command_utime == 0) return "";
  std::vector<std::string> items = words(s.last_command_result);
  if (now_utime > 0 && now_utime >= s.last_command_utime) {
    items.push_back("(" + age(static_cast<double>(now_utime - s.last_command_utime) * 1e-6) +
                    " ago)");
  }
  return wrap_items("command", items, kReportWidth, " ");
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
                       std::size_t width, std::string_view gap) {
  std::string out(label);
  out.resize(std::max(out.size() + 1, kLabelWidth), ' ');
  std::size_t column = out.size();
  bool first_on_line = true;
  for (const std::string& raw : items) {
    const std::string item = fit(raw, width - kLabelWidth);
    if (!first_on_line && column + gap.size() + item.size() > width) {
      out += "\n" + std::string(kLabelWidth, ' ');
      column = kLabelWidth;
      first_on_line = true;
    }
    if (!first_on_line) out += gap;
    out += item;
    column += (first_on_line ? 0 : gap.size()) + item.size();
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

std::vector<std::string> no_pair_items(const NoPairStretch& stretch) {
  if (stretch.span_s <= 0.0) return {};
  std::vector<std::string> items = {format("no longitudinal pair in %.0f s", stretch.span_s)};
  const std::size_t n = stretch.verdict_ticks.size();
  std::int64_t rest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& [name, ticks] = stretch.verdict_ticks[i];
    if (i < kVerdictsShown) {
      items.push_back(grouped(ticks) + (i == 0 ? " ticks " : " ") + printable(name));
    } else {
      rest += ticks;
    }
  }
  if (rest > 0) {
    items.push_back(format("%s in %zu other verdicts", grouped(rest).c_str(), n - kVerdictsShown));
  }
  // "...: a, b, c": the separators at the ends of the phrases, which wrap as a whole.
  if (items.size() > 1) items[0] += ":";
  for (std::size_t i = 1; i + 1 < items.size(); ++i) items[i] += ",";
  return items;
}

std::string monitor_report(const std::string& url, double estimate_hz, double status_hz,
                           const vmass::mass_estimate_t* estimate, const vmass::status_t* status,
                           const Silence& silence, const ReportContext& context) {
  std::string out = wrap_items("vmass-monitor", {url, format("estimates %.1f Hz", estimate_hz),
                                                 format("status %.2f Hz", status_hz)});
  if (const std::string message = silence_message(silence); !message.empty()) {
    out += wrap_items("SILENT", {message});
  }
  out += estimate ? estimate_lines(*estimate) : wrap_items("mass", {"(no estimate received)"});
  if (const auto why = no_pair_items(context.no_pair); !why.empty()) {
    out += wrap_items("why not", why, kReportWidth, " ");
  }
  if (status) {
    out += learnt_lines(*status) + tyre_watch_lines(*status) + pair_fit_lines(*status) +
           command_lines(*status, context.now_utime);
  }
  out += status ? status_lines(*status) : wrap_items("daemon", {"(no status received)"});
  return out;
}

}  // namespace vmass::monitor
