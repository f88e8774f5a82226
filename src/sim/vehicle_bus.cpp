#include "vmass/sim/vehicle_bus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "vmass/can/dbc.hpp"
#include "vmass/core/constants.hpp"
#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

namespace {

using Source = VehicleBus::Signal::Source;
using Signal = VehicleBus::Signal;
using Message = VehicleBus::Message;

constexpr double kDeg = kPi / 180.0;
constexpr double kG = 9.80665;

Signal make(Source src, std::string name, int byte, int length, bool is_signed, double factor,
            double offset, std::string unit, double si_per_unit, std::string input = "") {
  Signal s;
  s.source = src;
  s.name = std::move(name);
  s.byte = byte;
  s.length = length;
  s.is_signed = is_signed;
  s.factor = factor;
  s.offset = offset;
  s.unit = std::move(unit);
  s.si_per_unit = si_per_unit;
  s.input = std::move(input);
  // The physical range the raw field can hold, written as the DBC's [min|max].
  const double raw_max =
      is_signed ? std::ldexp(1.0, length - 1) - 1.0 : std::ldexp(1.0, length) - 1.0;
  const double raw_min = is_signed ? -std::ldexp(1.0, length - 1) : 0.0;
  s.minimum = raw_min * factor + offset;
  s.maximum = raw_max * factor + offset;
  return s;
}

// The SI value a signal carries, from the ECU signals (before noise and conventions).
double si_value(Source src, const EcuSignals& e, double odometer_m) {
  switch (src) {
    case Source::kWheelTorque:
      return e.wheel_torque_nm;
    case Source::kWheelTorqueFront:
      return 0.5 * e.wheel_torque_nm;
    case Source::kWheelTorqueRear:
      return 0.5 * e.wheel_torque_nm;
    case Source::kEngineTorque:
      return e.engine_torque_nm;
    case Source::kEngineSpeed:
      return e.engine_speed_radps;
    case Source::kGear:
      return static_cast<double>(e.gear);
    case Source::kAccelX:
      return e.accel_x_mps2;
    case Source::kAccelY:
      return e.accel_y_mps2;
    case Source::kYawRate:
      return e.yaw_rate_radps;
    case Source::kSpeed:
      return e.speed_mps;
    case Source::kBrakePressure:
      return e.brake_pressure_pa;
    case Source::kBrakeSwitch:
      return e.brake_light ? 1.0 : 0.0;
    case Source::kSteering:
      return e.steering_wheel_angle_rad;
    case Source::kLevelRearRight:
      return e.rear_right_deflection_m;
    case Source::kLevelOther:
      return 0.0;
    case Source::kDisplaySpeed:
      return e.display_speed_mps;
    case Source::kOdometer:
      return odometer_m;
    case Source::kMuxPage:
    case Source::kFiller:
      return 0.0;
  }
  return 0.0;
}

}  // namespace

VehicleBus::VehicleBus(const DrawnVehicle& vehicle) : vehicle_(vehicle) {
  build_messages();
  build_dbc();
}

namespace {

// Message layouts, one function per logical message, in the order they draw from one random
// stream. Every signal sits on whole bytes, so byte order never makes signals overlap.
class MessageLayout {
 public:
  explicit MessageLayout(const DrawnVehicle& v)
      : c_(v.can),
        s_(v.sensors),
        truck_(v.vehicle_class == VehicleClass::kHeavyTruck),
        engine_speed_(bus_has_engine_speed(v)),
        rng_(v.stream_seed(), hash_name("bus.layout")),
        next_id_(v.can.id_base) {}

  std::vector<Message> build() {
    std::vector<Message> out;
    out.push_back(powertrain());
    out.push_back(dynamics());
    if (s_.speed == SpeedSignal::kEsc) out.push_back(speed());
    out.push_back(brake());
    if (s_.lateral) out.push_back(steering());
    if (s_.deflection) out.push_back(level());
    out.push_back(cluster());
    others(out);
    return out;
  }

 private:
  Message message(std::string logical, std::string name, double period, double latency) {
    Message m;
    m.logical = std::move(logical);
    m.name = std::move(name);
    m.id = next_id_;
    next_id_ += 0x10 + 0x8 * static_cast<std::uint32_t>(rng_.index(3));
    m.extended = c_.extended_ids;
    if (m.extended) m.id |= 0x18FF0000u;
    m.period_s = period;
    m.latency_s = latency;
    m.phase_s = rng_.uniform(0.0, period);
    return m;
  }

  Message powertrain() {
    Message pt = message("powertrain", "PT_Torque", c_.torque_period_s, c_.torque_latency_s);
    const double tq = truck_ ? 2.0 : (rng_.chance(0.5) ? 0.5 : 1.0);
    if (s_.torque == TorqueSignal::kEngineTorque) {
      pt.signals.push_back(make(Source::kEngineTorque, "EngineTorque", 0, 16, true,
                                truck_ ? 1.0 : 0.25, 0.0, "Nm", 1.0, "engine_torque"));
      pt.signals.push_back(make(Source::kEngineSpeed, "EngineSpeed", 2, 16, false, 0.25, 0.0, "rpm",
                                2.0 * kPi / 60.0, "engine_speed"));
    } else if (s_.torque == TorqueSignal::kPerAxle) {
      pt.signals.push_back(make(Source::kWheelTorqueFront, "WheelTorque_Front", 0, 16, true, tq,
                                0.0, "Nm", 1.0, "wheel_torque"));
      pt.signals.push_back(make(Source::kWheelTorqueRear, "WheelTorque_Rear", 2, 16, true, tq, 0.0,
                                "Nm", 1.0, "wheel_torque"));
    } else {
      pt.signals.push_back(make(Source::kWheelTorque, "WheelTorque", 0, 16, true, tq, 0.0, "Nm",
                                1.0, "wheel_torque"));
      if (engine_speed_) {
        pt.signals.push_back(make(Source::kEngineSpeed, "EngineSpeed", 2, 16, false, 0.25, 0.0,
                                  "rpm", 2.0 * kPi / 60.0, "engine_speed"));
      }
    }
    if (s_.gear_index) {
      pt.signals.push_back(
          make(Source::kGear, "GearEngaged", 4, 8, true, 1.0, 0.0, "", 1.0, "gear"));
    }
    return pt;
  }

  Message dynamics() {
    Message dyn = message("dynamics", "ESC_Dynamics", c_.dynamics_period_s, c_.dynamics_latency_s);
    const double factor = c_.accel_in_g ? 0.0005 : (rng_.chance(0.5) ? 0.005 : 0.01);
    const std::string unit = c_.accel_in_g ? "g" : "m/s^2";
    const double si = c_.accel_in_g ? kG : 1.0;
    dyn.signals.push_back(
        make(Source::kAccelX, "LongAccel", 0, 16, true, factor, 0.0, unit, si, "accel_x"));
    if (!s_.lateral) return dyn;
    dyn.signals.push_back(
        make(Source::kAccelY, "LatAccel", 2, 16, true, factor, 0.0, unit, si, "accel_y"));
    Signal yaw =
        c_.yaw_in_rad
            ? make(Source::kYawRate, "YawRate", 4, 16, true, 0.0002, 0.0, "rad/s", 1.0, "yaw_rate")
            : make(Source::kYawRate, "YawRate", 4, 16, true, 0.01, 0.0, "deg/s", kDeg, "yaw_rate");
    yaw.sign = c_.yaw_positive_right ? -1.0 : 1.0;
    dyn.signals.push_back(yaw);
    return dyn;
  }

  Message speed() {
    Message spd = message("speed", "ESC_Speed", c_.speed_period_s, c_.speed_latency_s);
    spd.signals.push_back(make(Source::kSpeed, "VehicleSpeed", 0, 16, false,
                               rng_.chance(0.5) ? 0.01 : 0.0078125, 0.0, "km/h", 1.0 / 3.6,
                               "speed"));
    return spd;
  }

  Message brake() {
    Message brk = message("brake", "ESC_Brake", c_.brake_period_s, c_.brake_latency_s);
    if (s_.brake_pressure) {
      // Trucks: air pressure in bar; cars: hydraulic pressure in bar or kPa.
      const bool kpa = !truck_ && c_.pressure_in_kpa;
      const double factor = truck_ ? 0.001 : (kpa ? 1.0 : 0.01);
      brk.signals.push_back(make(Source::kBrakePressure, "BrakePressure", 0, 16, false, factor, 0.0,
                                 kpa ? "kPa" : "bar", kpa ? 1e3 : 1e5, "brake_pressure"));
    }
    brk.signals.push_back(make(Source::kBrakeSwitch, "BrakeLightSwitch", 2, 8, false, 1.0, 0.0, "",
                               1.0, s_.brake_pressure ? "" : "brake_switch"));
    return brk;
  }

  Message steering() {
    Message st = message("steering", "EPS_Steering", c_.steering_period_s, c_.steering_latency_s);
    Signal a = make(Source::kSteering, "SteeringWheelAngle", 0, 16, true,
                    rng_.chance(0.5) ? 0.1 : 0.04375, 0.0, "deg", kDeg, "steering_wheel_angle");
    a.sign = c_.steering_positive_right ? -1.0 : 1.0;
    st.signals.push_back(a);
    return st;
  }

  Message level() {
    Message lvl = message("level", "Chassis_Level", c_.level_period_s, c_.level_latency_s);
    const double f = rng_.chance(0.5) ? 0.1 : 0.01;
    if (!c_.deflection_muxed) {
      lvl.signals.push_back(make(Source::kLevelRearRight, "Level_RearRight", 0, 16, true, f, 0.0,
                                 "mm", 1e-3, "rear_right_deflection"));
      return lvl;
    }
    Signal page = make(Source::kMuxPage, "Level_Page", 0, 8, false, 1.0, 0.0, "", 1.0);
    page.is_switch = true;
    lvl.signals.push_back(page);
    Signal fl = make(Source::kLevelOther, "Level_FrontLeft", 1, 16, true, f, 0.0, "mm", 1e-3);
    Signal fr = make(Source::kLevelOther, "Level_FrontRight", 3, 16, true, f, 0.0, "mm", 1e-3);
    Signal rl = make(Source::kLevelOther, "Level_RearLeft", 1, 16, true, f, 0.0, "mm", 1e-3);
    Signal rr = make(Source::kLevelRearRight, "Level_RearRight", 3, 16, true, f, 0.0, "mm", 1e-3,
                     "rear_right_deflection");
    fl.mux = fr.mux = 0;
    rl.mux = rr.mux = 1;
    lvl.signals.insert(lvl.signals.end(), {fl, fr, rl, rr});
    return lvl;
  }

  Message cluster() {
    Message ic = message("cluster", "IC_Display", c_.display_period_s, c_.display_latency_s);
    ic.protected_frame = false;
    ic.length = 6;
    ic.signals.push_back(make(Source::kDisplaySpeed, "DisplaySpeed", 0, 16, false,
                              rng_.chance(0.5) ? 1.0 : 0.5, 0.0, "km/h", 1.0 / 3.6,
                              s_.speed == SpeedSignal::kDisplay ? "speed" : ""));
    ic.signals.push_back(make(Source::kOdometer, "Odometer", 2, 32, false, 0.1, 0.0, "km", 1000.0));
    return ic;
  }

  // Other ECUs: the bus is never only what the estimator reads.
  void others(std::vector<Message>& out) {
    const char* names[] = {"ECM_Temperatures", "HVAC_Status", "BCM_Doors", "TCU_Status"};
    const int n = 2 + rng_.index(3);
    for (int i = 0; i < n; ++i) {
      Message o = message("other", names[i], 0.02 * (1 + rng_.index(10)), 0.0);
      o.signals.push_back(
          make(Source::kFiller, std::string(names[i]) + "_A", 0, 16, false, 0.1, -40.0, "", 1.0));
      o.signals.push_back(
          make(Source::kFiller, std::string(names[i]) + "_B", 2, 8, false, 1.0, 0.0, "", 1.0));
      out.push_back(o);
    }
  }

  const CanConventions& c_;
  const VehicleSensors& s_;
  bool truck_;
  bool engine_speed_;  ///< bus_has_engine_speed
  RandomStream rng_;
  std::uint32_t next_id_;
};

}  // namespace

void VehicleBus::build_messages() { messages_ = MessageLayout(vehicle_).build(); }

namespace {

// DBC start bit of a byte-aligned field: Intel counts from the LSB, Motorola names the MSB.
int start_bit(int byte, int length, bool motorola) {
  if (!motorola) return byte * 8;
  if (length < 8) return byte * 8 + length - 1;
  return byte * 8 + 7;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

void VehicleBus::build_dbc() {
  const bool motorola = vehicle_.can.motorola;
  std::ostringstream os;
  os << "VERSION \"vmass population vehicle " << vehicle_.id << "\"\n\n\nNS_ :\n\tCM_\n\tBA_DEF_\n"
     << "\tBA_\n\tVAL_\n\tBA_DEF_DEF_\n\nBS_:\n\nBU_: PCM ESC EPS LVL IC BCM VMASS\n\n";
  for (const Message& m : messages_) {
    const std::uint32_t dbc_id = m.extended ? (m.id | can::kDbcExtendedBit) : m.id;
    os << "BO_ " << dbc_id << ' ' << m.name << ": " << m.length << " PCM\n";
    for (const Signal& s : m.signals) {
      std::string mux;
      if (s.is_switch) mux = " M";
      if (s.mux >= 0) mux = " m" + std::to_string(s.mux);
      os << " SG_ " << s.name << mux << " : " << start_bit(s.byte, s.length, motorola) << '|'
         << s.length << '@' << (motorola ? '0' : '1') << (s.is_signed ? '-' : '+') << " ("
         << number(s.factor) << ',' << number(s.offset) << ") [" << number(s.minimum) << '|'
         << number(s.maximum) << "] \"" << s.unit << "\" VMASS\n";
    }
    if (m.protected_frame) {
      os << " SG_ " << m.name << "_Checksum : " << start_bit(6, 8, motorola) << "|8@"
         << (motorola ? '0' : '1') << "+ (1,0) [0|255] \"\" VMASS\n";
      os << " SG_ " << m.name << "_Counter : " << start_bit(7, 4, motorola) << "|4@"
         << (motorola ? '0' : '1') << "+ (1,0) [0|15] \"\" VMASS\n";
    }
    os << '\n';
  }
  os << "\nCM_ \"Population vehicle " << vehicle_.id
     << " written by vmass-sim: " << describe_vehicle(vehicle_) << "\";\n";
  os << "BA_DEF_ BO_ \"GenMsgCycleTime\" INT 0 10000;\nBA_DEF_DEF_ \"GenMsgCycleTime\" 0;\n";
  for (const Message& m : messages_) {
    const std::uint32_t dbc_id = m.extended ? (m.id | can::kDbcExtendedBit) : m.id;
    os << "BA_ \"GenMsgCycleTime\" BO_ " << dbc_id << ' '
       << static_cast<int>(std::lround(m.period_s * 1000.0)) << ";\n";
  }
  dbc_text_ = os.str();

  can::DbcParseResult parsed = can::parse_dbc(dbc_text_, vehicle_.id + ".dbc");
  if (!parsed.ok()) {
    for (const auto& d : parsed.diagnostics) {
      if (d.severity == can::Severity::kError) error_ = d.to_string();
    }
    if (error_.empty()) error_ = "the generated DBC did not parse";
    return;
  }
  std::optional<can::Decoder> decoder = can::Decoder::compile(std::move(parsed.database), &error_);
  if (decoder) decoder_.push_back(std::move(*decoder));
}

std::string VehicleBus::can_config_yaml(const std::string& dbc_file) const {
  std::ostringstream os;
  os << "can:\n  dbc: " << dbc_file << "\n  inputs:\n";
  // Inputs in a fixed order; a sum where several signals feed one input.
  const char* order[] = {"wheel_torque",
                         "engine_torque",
                         "engine_speed",
                         "gear",
                         "brake_pressure",
                         "brake_switch",
                         "accel_x",
                         "accel_y",
                         "yaw_rate",
                         "speed",
                         "steering_wheel_angle",
                         "rear_right_deflection"};
  for (const char* input : order) {
    std::vector<std::pair<const Message*, const Signal*>> terms;
    for (const Message& m : messages_) {
      for (const Signal& s : m.signals) {
        if (s.input == input) terms.emplace_back(&m, &s);
      }
    }
    if (terms.empty()) continue;
    auto term = [](const Message& m, const Signal& s) {
      std::string t = "{message: " + m.name + ", signal: " + s.name;
      if (s.mux >= 0) t += ", mux: " + std::to_string(s.mux);
      if (s.sign < 0.0) t += ", gain: -1";
      return t + "}";
    };
    if (terms.size() == 1) {
      os << "    " << input << ": " << term(*terms[0].first, *terms[0].second) << '\n';
    } else {
      os << "    " << input << ":\n      sum:\n";
      for (const auto& [m, s] : terms) os << "        - " << term(*m, *s) << '\n';
    }
  }
  return os.str();
}

namespace {

// Samples the EcuSignals trace at time t (nearest integration step at or before it).
const EcuSignals& trace_at(const SimulationResult& r, double t_s) {
  const auto n = static_cast<long>(r.ecu_trace.size());
  long i = static_cast<long>(std::floor(t_s * r.ecu_trace_rate_hz + 1e-6));
  i = std::clamp(i, 0L, n - 1);
  return r.ecu_trace[static_cast<std::size_t>(i)];
}

double odometer_at(const SimulationResult& r, double t_s) {
  const auto k = static_cast<long>(std::floor(t_s * r.tick_rate_hz + 1e-6));
  const long n = static_cast<long>(r.truth.size());
  return r.truth[static_cast<std::size_t>(std::clamp(k, 0L, n - 1))].distance_m;
}

struct NoiseStreams {
  explicit NoiseStreams(std::uint64_t seed)
      : accel(seed, hash_name("bus.noise.accel")),
        gyro(seed, hash_name("bus.noise.gyro")),
        other(seed, hash_name("bus.noise.other")),
        eps(seed, hash_name("bus.noise.eps")),
        filler(seed, hash_name("bus.filler")) {}
  RandomStream accel, gyro, other, eps, filler;
};

double eps_force_n(NoiseSet set, RandomStream& rng) {
  switch (set) {
    case NoiseSet::kNone:
      return 0.0;
    case NoiseSet::kEps1:
      return 60.0 * rng.normal();
    case NoiseSet::kEps2:
      return 300.0 + 60.0 * rng.normal();
    case NoiseSet::kEps3:
      return 600.0 * rng.uniform();
  }
  return 0.0;
}

const BusFault* active_fault(const std::vector<BusFault>& faults, const std::string& logical,
                             BusFault::Kind kind, double t_s) {
  for (const BusFault& f : faults) {
    if (f.kind == kind && f.message == logical && t_s >= f.start_s &&
        t_s < f.start_s + f.duration_s) {
      return &f;
    }
  }
  return nullptr;
}

}  // namespace

namespace {

// Encodes the frames of one drive (VehicleBus::encode): one message at a time.
class FrameEncoder {
 public:
  FrameEncoder(const can::Decoder& decoder, const SimulationResult& result,
               const BusOptions& options)
      : decoder_(decoder),
        result_(result),
        options_(options),
        timing_(options.realism.has(Effect::kBusTiming)),
        noise_(options.realism.has(Effect::kSensorNoise)),
        end_s_(static_cast<double>(result.ecu_trace.size() - 1) / result.ecu_trace_rate_hz),
        rng_(options.seed),
        values_(static_cast<std::size_t>(decoder.max_signals_per_message())) {}

  /// Every frame of message m (the mi-th on the bus). "" or a message.
  std::string encode_message(const Message& m, std::size_t mi, std::vector<can::CanFrame>* out) {
    const int index = decoder_.find_message(m.name);
    if (index < 0) return "encode: no message " + m.name + " in the generated DBC";
    const bool slow = m.logical == "cluster" || m.logical == "other";
    const double period = timing_ || slow ? m.period_s : 0.01;
    const double phase = timing_ ? m.phase_s : 0.0;
    const double latency = timing_ ? m.latency_s : 0.0;
    const auto tx_us = static_cast<TimeUs>(150 * (mi + 1));  // arbitration order on the bus
    int page = 0;
    for (long j = 0;; ++j) {
      const double t = phase + static_cast<double>(j) * period;
      if (t > end_s_) break;
      if (fault(m.logical, BusFault::Kind::kMissing, t) != nullptr) continue;
      double t_value = t - latency;
      if (const BusFault* f = fault(m.logical, BusFault::Kind::kFrozen, t)) {
        t_value = f->start_s - latency;
      }
      const bool absurd = fault(m.logical, BusFault::Kind::kAbsurd, t) != nullptr &&
                          fault(m.logical, BusFault::Kind::kAbsurd, t - period) == nullptr;
      can::CanFrame f = frame(m, index, std::max(0.0, t_value), page, absurd);
      f.time_us = from_seconds(t) + tx_us;
      if (m.protected_frame) protect(m, j, &f);
      if (fault(m.logical, BusFault::Kind::kMalformedBurst, t) != nullptr) f.len = 2;
      out->push_back(f);
      if (!m.signals.empty() && m.signals.front().is_switch) page = 1 - page;
    }
    return "";
  }

  /// Frames with identifiers the DBC does not know, for each unknown-burst fault.
  void unknown_bursts(std::vector<can::CanFrame>* out) {
    for (const BusFault& fault : options_.faults) {
      if (fault.kind != BusFault::Kind::kUnknownBurst) continue;
      const int count = static_cast<int>(fault.duration_s * 2000.0);
      for (int i = 0; i < count; ++i) {
        can::CanFrame f;
        f.id = 0x700u + static_cast<std::uint32_t>(rng_.filler.index(0xF0));
        f.len = static_cast<std::uint8_t>(1 + rng_.filler.index(8));
        for (int b = 0; b < f.len; ++b)
          f.data[b] = static_cast<std::uint8_t>(rng_.filler.index(256));
        f.time_us = from_seconds(fault.start_s + static_cast<double>(i) / 2000.0) + 77;
        out->push_back(f);
      }
    }
  }

 private:
  const BusFault* fault(const std::string& logical, BusFault::Kind kind, double t) const {
    return active_fault(options_.faults, logical, kind, t);
  }

  can::CanFrame frame(const Message& m, int index, double t_value, int page, bool absurd) {
    const EcuSignals& e = trace_at(result_, t_value);
    const double odo = odometer_at(result_, t_value);
    std::fill(values_.begin(), values_.end(), 0.0);
    const can::Message& def = decoder_.database().messages[static_cast<std::size_t>(index)];
    for (const Signal& s : m.signals) {
      const int si = def.find_signal(s.name);
      if (si < 0) continue;
      double physical = page;
      if (!s.is_switch) {
        if (s.mux >= 0 && s.mux != page) continue;
        physical = s.sign * transmitted(s, e, odo) / s.si_per_unit;
        if (absurd && s.source != Source::kGear) physical = s.maximum;
      }
      values_[static_cast<std::size_t>(si)] = physical;
    }
    can::CanFrame f;
    decoder_.encode(index, values_.data(), &f);
    return f;
  }

  // The value an ECU transmits: the signal with the torque's scale error and eps noise, or the
  // sensor's white noise.
  double transmitted(const Signal& s, const EcuSignals& e, double odometer_m) {
    const TrueVehicle& tv = result_.vehicle;
    const double v = si_value(s.source, e, odometer_m);
    switch (s.source) {
      case Source::kWheelTorque:
      case Source::kWheelTorqueFront:
      case Source::kWheelTorqueRear: {
        const double share = s.source == Source::kWheelTorque ? 1.0 : 0.5;
        return v * options_.torque_report_scale +
               share * eps_force_n(options_.eps, rng_.eps) * tv.wheel_radius_m;
      }
      case Source::kEngineTorque: {
        const PowertrainParams& p = tv.powertrain;
        const int g = std::clamp(e.gear, 1, p.gear_count());
        const double ratio =
            p.gear_ratios[static_cast<std::size_t>(g - 1)] * p.final_drive_ratio * p.efficiency;
        return v * options_.torque_report_scale +
               eps_force_n(options_.eps, rng_.eps) * tv.wheel_radius_m / ratio;
      }
      case Source::kAccelX:
      case Source::kAccelY:
        return noise_ ? v + tv.imu.noise_std_mps2 * rng_.accel.normal() : v;
      case Source::kYawRate:
        return noise_ ? v + tv.imu.gyro_noise_std_radps * rng_.gyro.normal() : v;
      case Source::kSpeed:
        return noise_ && v > 0.0 ? std::max(0.0, v + 0.02 * rng_.other.normal()) : v;
      case Source::kBrakePressure:
        return noise_ ? std::max(0.0, v + 3000.0 * rng_.other.normal()) : v;
      case Source::kSteering:
        return noise_ ? v + 0.1 * kDeg * rng_.other.normal() : v;
      case Source::kLevelRearRight:
        return noise_ ? v + 1.5e-4 * rng_.other.normal() : v;
      case Source::kFiller:
        return rng_.filler.uniform(0.0, 100.0);
      default:
        return v;
    }
  }

  // A 4-bit rolling counter in byte 7's low nibble, an XOR of the id and bytes 0..5 in byte 6.
  static void protect(const Message& m, long j, can::CanFrame* f) {
    f->data[7] = static_cast<std::uint8_t>((f->data[7] & 0xF0u) | (j & 0x0F));
    auto x = static_cast<std::uint8_t>(m.id & 0xFFu);
    for (int b = 0; b < 6; ++b) x ^= f->data[b];
    f->data[6] = x;
  }

  const can::Decoder& decoder_;
  const SimulationResult& result_;
  const BusOptions& options_;
  bool timing_, noise_;
  double end_s_;
  NoiseStreams rng_;
  std::vector<double> values_;
};

}  // namespace

std::string VehicleBus::encode(const SimulationResult& result, const BusOptions& options,
                               std::vector<can::CanFrame>* frames) const {
  if (!error_.empty()) return vehicle_.id + ": " + error_;
  if (result.ecu_trace.empty()) return "encode: the simulation kept no ECU trace";
  FrameEncoder encoder(decoder_.front(), result, options);
  frames->clear();
  for (std::size_t mi = 0; mi < messages_.size(); ++mi) {
    if (auto m = encoder.encode_message(messages_[mi], mi, frames); !m.empty()) return m;
  }
  encoder.unknown_bursts(frames);
  std::stable_sort(
      frames->begin(), frames->end(),
      [](const can::CanFrame& a, const can::CanFrame& b) { return a.time_us < b.time_us; });
  return "";
}

}  // namespace vmass::sim
