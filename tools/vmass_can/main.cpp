// vmass-can: the CAN layer from the command line.
//
//   vmass-can check  --dbc FILE [--strict]            validate a DBC, list messages and signals
//   vmass-can decode --dbc FILE [LOG] [--json]        decode a CAN log (stdin without LOG): candump
//                    [--interface NAME]               -l or screen output, Vector ASC or BLF,
//                                                     PEAK TRC, ASAM MDF4
//                                                     (runtime/log_frame_source); one interface
//                                                     of it with --interface
//   vmass-can dump   --can IFACE [--count N] [--idle-timeout S] [--dbc FILE]
//                                                     print frames from SocketCAN as candump -l
//
// Exit codes (tools/common/exit_code.hpp): 0 ok; 1 failure (SocketCAN cannot be opened, dump
// got fewer than --count frames before the idle timeout, a read error in the log); 2 usage or
// input error (a DBC with errors, or with deviations under --strict: check reports every one,
// decode decodes with what loaded and still exits 2; a log that cannot be opened or is no CAN
// log, or has no frame on --interface); decode exits 1 when the MDF4 converter failed on the
// way.
#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "exit_code.hpp"
#include "interface_option.hpp"
#include "subcommands_formatter.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/can/socketcan.hpp"
#include "vmass/json/json.hpp"
#include "vmass/runtime/log_frame_source.hpp"
#include "vmass/runtime/text_log_frame_source.hpp"

namespace {

using namespace vmass::can;
namespace rt = vmass::runtime;

void print_diagnostics(const DbcParseResult& r) {
  for (const DbcDiagnostic& d : r.diagnostics) std::cerr << d.to_string() << "\n";
}

/// Shortest text that reads back as the same double; JSON null for NaN and infinities.
void append_number(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// The DBC compiled for decoding; *had_errors when it loaded only in part (what loaded is still
/// decoded, and the run then exits 2).
std::optional<Decoder> load_decoder(const std::string& path, bool strict, bool quiet_warnings,
                                    bool* had_errors) {
  DbcParseOptions opt;
  opt.strict = strict;
  DbcParseResult r = load_dbc_file(path, opt);
  for (const DbcDiagnostic& d : r.diagnostics) {
    if (d.severity == Severity::kError || !quiet_warnings) std::cerr << d.to_string() << "\n";
  }
  if (r.diagnostics.size() == 1 && r.diagnostics[0].line == 0 &&
      r.diagnostics[0].severity == Severity::kError) {
    return std::nullopt;  // unreadable, empty
  }
  *had_errors = !r.ok();
  if (!r.ok()) {
    if (strict) return std::nullopt;
    std::cerr << path << ": " << r.error_count()
              << " error(s); decoding with what could be loaded (exit code 2)\n";
  }
  std::string error;
  auto d = Decoder::compile(std::move(r.database), &error);
  if (!d) std::cerr << path << ": " << error << "\n";
  return d;
}

int run_check(const std::string& dbc, bool strict) {
  DbcParseOptions opt;
  opt.strict = strict;
  DbcParseResult r = load_dbc_file(dbc, opt);
  print_diagnostics(r);
  const Database& db = r.database;
  std::size_t signal_count = 0;
  for (const Message& m : db.messages) {
    signal_count += m.signals.size();
    std::printf("%s 0x%X%s %s: %d bytes%s", m.extended ? "EXT" : "STD", m.id, "", m.name.c_str(),
                m.length, m.fd ? " FD" : "");
    if (m.cycle_time_ms > 0) std::printf(", every %d ms", m.cycle_time_ms);
    std::printf(", %zu signals\n", m.signals.size());
    for (const Signal& s : m.signals) {
      std::printf("  %s %d|%d@%c%c (%.17g,%.17g)", s.name.c_str(), s.start_bit, s.length,
                  s.byte_order == ByteOrder::kIntel ? '1' : '0', s.is_signed ? '-' : '+', s.factor,
                  s.offset);
      if (s.has_range) std::printf(" [%.17g|%.17g]", s.minimum, s.maximum);
      if (!s.unit.empty()) std::printf(" \"%s\"", s.unit.c_str());
      if (s.value_type == ValueType::kFloat32) std::printf(" float32");
      if (s.value_type == ValueType::kFloat64) std::printf(" float64");
      if (s.is_multiplexor) std::printf(" multiplexor");
      if (s.mux_parent >= 0) {
        std::printf(" when %s in", m.signals[static_cast<std::size_t>(s.mux_parent)].name.c_str());
        for (const MuxRange& rg : s.mux_ranges) {
          if (rg.lo == rg.hi) {
            std::printf(" %llu", static_cast<unsigned long long>(rg.lo));
          } else {
            std::printf(" %llu-%llu", static_cast<unsigned long long>(rg.lo),
                        static_cast<unsigned long long>(rg.hi));
          }
        }
      }
      std::printf("\n");
    }
  }
  std::string error;
  const bool compiles = Decoder::compile(db, &error).has_value();
  if (!compiles) std::cerr << dbc << ": " << error << "\n";
  std::printf("%s: %zu messages, %zu signals, %d warning(s), %d error(s)%s\n", dbc.c_str(),
              db.messages.size(), signal_count, r.warning_count(), r.error_count(),
              strict ? " (strict)" : "");
  return r.ok() && compiles ? vmass::tools::kExitOk : vmass::tools::kExitUsage;
}

/// One decoded frame as a JSON object (a line). The time is the double nearest the log's
/// microseconds in seconds (the quotient of two exact doubles is rounded once).
void append_json(std::string& out, const Decoder& decoder, const Message& msg,
                 const CandumpRecord& rec) {
  namespace json = vmass::json;
  json::Json j;
  j["time_s"] = static_cast<double>(rec.frame.time_us) / 1e6;
  j["id"] = rec.frame.id;
  j["message"] = msg.name;
  json::Json& signals = j["signals"] = json::Json::object();
  decoder.decode(rec.frame, [&](int i, double v) {
    signals[msg.signals[static_cast<std::size_t>(i)].name] = json::number(v);
  });
  out += json::dump(j);
  out += '\n';
}

/// One decoded frame as cantools decode prints it: the candump line, then the signals (value
/// descriptions for integer signals that have one, else the value and the unit).
void append_text(std::string& out, const Decoder& decoder, const Message& msg,
                 const CandumpRecord& rec) {
  std::string line = format_candump_line(rec.frame, rec.interface);
  line.pop_back();
  out += line + " :: " + msg.name + "(";
  bool first = true;
  decoder.decode(rec.frame, [&](int i, double v) {
    const Signal& s = msg.signals[static_cast<std::size_t>(i)];
    if (!first) out += ", ";
    first = false;
    out += s.name + ": ";
    const double raw = std::round((v - s.offset) / s.factor);
    const ValueDescription* choice = nullptr;
    for (const ValueDescription& vd : s.values) {
      if (static_cast<double>(vd.value) == raw) choice = &vd;
    }
    if (choice != nullptr && s.value_type == ValueType::kInteger) {
      out += "'" + choice->text + "'";
    } else {
      append_number(out, v);
      if (!s.unit.empty()) out += " " + s.unit;
    }
  });
  out += ")\n";
}

/// The log to decode: a file of any format vmass reads, or standard input (text formats); its
/// interface `interface` alone unless "".
std::unique_ptr<rt::LogFrameSource> open_decode_input(const std::string& log,
                                                      const std::string& interface) {
  std::string error;
  std::unique_ptr<rt::LogFrameSource> source;
  if (log.empty() || log == "-") {
    source = rt::TextLogFrameSource::from_stream(std::make_unique<std::istream>(std::cin.rdbuf()),
                                                 "stdin", false, &error);
  } else {
    source = rt::open_log_frame_source(log, &error, false);
  }
  if (!source) std::cerr << "vmass-can decode: " << error << "\n";
  if (source && !interface.empty()) source->select_interface(interface);
  return source;
}

/// Decodes every frame of the log to stdout; undecodable frames are echoed (text) or left out
/// (JSON), too-short ones reported with their line (record).
DecodeStats decode_frames(rt::LogFrameSource& source, const Decoder& decoder, bool json) {
  const Database& db = decoder.database();
  DecodeStats stats;
  CandumpRecord rec;
  std::string out;
  out.reserve(4096);
  while (source.read(&rec.frame, 0) == rt::FrameSource::Read::kFrame) {
    rec.interface = source.interface_name();
    int m = -1;
    out.clear();
    const DecodeStatus st = decoder.classify(rec.frame, &m);
    stats.count(st);
    if (st != DecodeStatus::kOk) {
      if (st == DecodeStatus::kTooShort) {
        std::cerr << source.path() << ":" << (source.unit() == "record" ? "record " : "")
                  << source.position() << ": frame "
                  << db.messages[static_cast<std::size_t>(m)].name << " has " << int(rec.frame.len)
                  << " bytes, the DBC says " << db.messages[static_cast<std::size_t>(m)].length
                  << ": rejected\n";
      }
      if (!json) std::cout << format_candump_line(rec.frame, rec.interface);
      continue;
    }
    const Message& msg = db.messages[static_cast<std::size_t>(m)];
    if (json) {
      append_json(out, decoder, msg, rec);
    } else {
      append_text(out, decoder, msg, rec);
    }
    std::cout << out;
  }
  std::cout.flush();
  return stats;
}

/// ", N frames of other interfaces skipped" with --interface, else "".
std::string skipped_report(const rt::LogFrameSource& source) {
  const rt::InterfaceSelection* selection = source.interface_selection();
  if (selection == nullptr) return "";
  return ", " + std::to_string(selection->skipped()) + " frames of other interfaces skipped";
}

int run_decode(const std::string& dbc, const std::string& log, const std::string& interface,
               bool json, bool strict) {
  bool dbc_errors = false;
  auto decoder = load_decoder(dbc, strict, json, &dbc_errors);
  if (!decoder) return vmass::tools::kExitUsage;
  std::unique_ptr<rt::LogFrameSource> source = open_decode_input(log, interface);
  if (!source) return vmass::tools::kExitUsage;
  source->on_error([](const CandumpError& e) { std::cerr << e.message << "\n"; });
  const DecodeStats stats = decode_frames(*source, *decoder, json);
  const CandumpStats& cs = source->stats();
  std::cerr << "vmass-can decode: " << log_format_name(source->format()) << ", " << cs.frames
            << " frames, " << stats.decoded << " decoded, " << stats.unknown_id << " unknown id, "
            << stats.too_short << " too short, " << stats.remote << " remote, "
            << stats.error_frames << " error frames, " << cs.corrupt << " corrupt "
            << source->unit() << "s" << skipped_report(*source) << "\n";
  if (dbc_errors) return vmass::tools::kExitUsage;
  if (source->problem().empty()) {
    // Not one line could be read, or no frame was on --interface.
    const std::string no_frames = source->no_frames_reason();
    if (no_frames.empty()) return vmass::tools::kExitOk;
    std::cerr << "vmass-can decode: " << no_frames << "\n";
    return vmass::tools::kExitUsage;
  }
  // A converter's failure was reported with the records; a read error is said here.
  if (!vmass::can::is_converted_format(source->format())) std::cerr << source->problem() << "\n";
  return vmass::tools::kExitFailure;
}

int run_dump(const std::string& iface, long count, double idle_timeout_s, const std::string& dbc) {
  SocketCanOptions opt;
  opt.interface = iface;
  opt.reopen_initial_ms = 50;
  opt.reopen_max_ms = 1000;
  if (!dbc.empty()) {
    DbcParseResult r = load_dbc_file(dbc);
    print_diagnostics(r);
    opt.filters = filters_for(r.database);
  }
  std::string error;
  auto reader = SocketCanReader::open(opt, &error);
  if (!reader) {
    std::cerr << "vmass-can dump: " << error << "\n";
    return 1;
  }
  std::cerr << "vmass-can dump: listening on " << iface << "\n";
  long got = 0;
  CanFrame f;
  const int step_ms = 100;
  double idle_s = 0.0;
  std::uint64_t reopens = 0;
  while (count <= 0 || got < count) {
    const ReadStatus st = reader->read(&f, step_ms);
    if (reader->stats().reopens != reopens) {
      reopens = reader->stats().reopens;
      std::cerr << "vmass-can dump: socket re-created on " << iface << "\n";
    }
    if (st == ReadStatus::kFrame) {
      idle_s = 0.0;
      ++got;
      std::cout << format_candump_line(f, iface) << std::flush;
      continue;
    }
    if (st != ReadStatus::kTimeout && st != ReadStatus::kReopening) {
      std::cerr << "vmass-can dump: " << read_status_name(st) << ": " << reader->last_error()
                << "\n";
    }
    if (st == ReadStatus::kClosed) break;
    idle_s += st == ReadStatus::kInterfaceDown || st == ReadStatus::kInterfaceGone ? 0.0 : 0.1;
    if (idle_timeout_s > 0 && idle_s >= idle_timeout_s) break;
  }
  const SocketCanStats& s = reader->stats();
  std::cerr << "vmass-can dump: " << got << " frames (" << s.fd_frames << " FD, " << s.error_frames
            << " error), " << s.dropped << " dropped, " << s.interface_down << " interface down, "
            << s.interface_gone << " interface gone, " << s.reopens << " re-opened, "
            << s.no_kernel_timestamp << " without kernel timestamp\n";
  return count > 0 && got < count ? vmass::tools::kExitFailure : vmass::tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vmass-can: DBC checking, candump log decoding and SocketCAN dumping"};
  app.require_subcommand(1);
  // Every subcommand's options at once (the man page is help2man's reading of it); set before
  // the subcommands, which take the formatter along.
  app.formatter(std::make_shared<vmass::tools::SubcommandsFormatter>());
  app.set_help_all_flag("--help-all", "print this help with every subcommand's options, then exit");

  std::string dbc, log, iface, decode_interface;
  bool strict = false, json = false;
  long count = 0;
  double idle_timeout_s = 0.0;

  CLI::App* check = app.add_subcommand("check", "validate a DBC file, list messages and signals");
  check->add_option("--dbc", dbc, "DBC file")->required();
  check->add_flag("--strict", strict, "treat deviations from the format as errors");

  CLI::App* decode = app.add_subcommand("decode", "decode a CAN log with a DBC file");
  decode->add_option("--dbc", dbc, "DBC file")->required();
  decode->add_option("log", log,
                     "CAN log: candump -l or screen output, Vector ASC/BLF, PEAK TRC, ASAM MDF4 "
                     "(default: standard input, a text format)");
  decode->add_flag("--json", json, "one JSON object per decoded frame");
  decode->add_flag("--strict", strict, "refuse a DBC with deviations");
  vmass::tools::add_interface_option(*decode, &decode_interface);

  CLI::App* dump = app.add_subcommand("dump", "print frames from a SocketCAN interface");
  dump->add_option("--can", iface, "interface, e.g. can0")->required();
  dump->add_option("--count", count, "stop after this many frames (0: never)");
  dump->add_option("--idle-timeout", idle_timeout_s, "stop after this long without frames, s");
  dump->add_option("--dbc", dbc, "receive only this DBC's ids");

  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;
  if (check->parsed()) return run_check(dbc, strict);
  if (decode->parsed()) return run_decode(dbc, log, decode_interface, json, strict);
  return run_dump(iface, count, idle_timeout_s, dbc);
}
