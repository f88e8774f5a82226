// vmass._vmass: the native half of the Python package (python/vmass wraps it): the config as
// the tools read it, and one log replayed with the GIL released (replay_session.hpp), its
// estimates handed over as NumPy arrays without a copy.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <utility>
#include <vector>

#include "replay_session.hpp"
#include "vmass/version.hpp"

namespace nb = nanobind;
using vmass::python::EstimateColumns;
using vmass::python::ReplayOutcome;

namespace {

/// The vector as a 1-D NumPy array that owns it (freed when the array is).
template <class T>
nb::ndarray<nb::numpy, T, nb::ndim<1>> to_numpy(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T, nb::ndim<1>>(owned->data(), {owned->size()}, owner);
}

/// The columns in the estimate CSV's order.
nb::dict columns_dict(EstimateColumns&& c) {
  nb::dict d;
  d["time_s"] = to_numpy(std::move(c.time_s));
  d["mass_kg"] = to_numpy(std::move(c.mass_kg));
  d["mass_ci_low_kg"] = to_numpy(std::move(c.mass_ci_low_kg));
  d["mass_ci_high_kg"] = to_numpy(std::move(c.mass_ci_high_kg));
  d["mu_n"] = to_numpy(std::move(c.mu_n));
  d["status"] = to_numpy(std::move(c.status));
  d["mass_std_kg"] = to_numpy(std::move(c.mass_std_kg));
  d["reason"] = to_numpy(std::move(c.reason));
  d["longitudinal_pairs"] = to_numpy(std::move(c.longitudinal_pairs));
  d["lateral_pairs"] = to_numpy(std::move(c.lateral_pairs));
  d["longitudinal_availability"] = to_numpy(std::move(c.longitudinal_availability));
  d["lateral_availability"] = to_numpy(std::move(c.lateral_availability));
  d["initial_mass_kg"] = to_numpy(std::move(c.initial_mass_kg));
  return d;
}

nb::dict outcome_dict(ReplayOutcome&& o) {
  nb::dict d;
  d["error"] = o.error;
  d["bad_input"] = o.bad_input;
  d["columns"] = columns_dict(std::move(o.estimates));
  d["summary_json"] = o.summary_json;
  d["log_format"] = o.log_format;
  d["frames"] = o.frames;
  d["corrupt_lines"] = o.corrupt;
  d["other_interface_frames"] = o.other_interface_frames;
  d["warnings"] = o.warnings;
  d["state_message"] = o.state_message;
  d["state_restored"] = o.state_restored;
  d["state_saved"] = o.state_saved;
  d["state_save_error"] = o.state_save_error;
  return d;
}

/// The loaded config; null and the error ("file:line: key: message") when it is refused.
nb::tuple load_config(const std::string& path) {
  vmass::python::ConfigResult r = vmass::python::load_replay_config(path);
  return nb::make_tuple(r.config, r.error);
}

nb::dict replay_log(const std::shared_ptr<const vmass::Config>& config, const std::string& log,
                    const vmass::python::ReplayOptions& options) {
  ReplayOutcome outcome;
  {
    nb::gil_scoped_release unlocked;  // other Python threads run while the log replays
    outcome = vmass::python::replay_log(*config, log, options);
  }
  return outcome_dict(std::move(outcome));
}

}  // namespace

NB_MODULE(_vmass, m) {
  m.doc() = "vmass native bindings (use the package vmass, not this module)";
  m.attr("__version__") = vmass::kVersion;
  nb::class_<vmass::Config>(m, "Config")
      .def_prop_ro("max_mass_kg",
                   [](const vmass::Config& c) { return c.pipeline.vehicle.max_mass_kg; })
      .def_prop_ro("empty_mass_kg",
                   [](const vmass::Config& c) { return c.pipeline.vehicle.empty_mass_kg; })
      .def_prop_ro("tick_rate_hz", [](const vmass::Config& c) {
        return c.pipeline.estimator.differencing.tick_rate_hz;
      });
  nb::class_<vmass::python::ReplayOptions>(m, "ReplayOptions")
      .def(nb::init<>())
      .def_rw("interface", &vmass::python::ReplayOptions::interface)
      .def_rw("estimator", &vmass::python::ReplayOptions::estimator)
      .def_rw("truth_path", &vmass::python::ReplayOptions::truth_path)
      .def_rw("known_masses", &vmass::python::ReplayOptions::known_masses)
      .def_rw("state_path", &vmass::python::ReplayOptions::state_path);
  m.def("load_config", &load_config, nb::arg("path"));
  m.def("replay_log", &replay_log, nb::arg("config"), nb::arg("log"), nb::arg("options"));
  m.def("status_names", &vmass::python::status_names);
  m.def("reason_names", &vmass::python::reason_names);
}
