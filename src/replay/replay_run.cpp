#include "vmass/replay/replay_run.hpp"

namespace vmass {

std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           const std::vector<KnownMassEvent>& known_masses,
                           scoring::ReplaySummary* summary, const EstimateSink& sink,
                           runtime::TickRun* run) {
  const double rate_hz = step.pipeline().params().estimator.differencing.tick_rate_hz;
  const TimeUs tick_period_us = from_seconds(1.0 / rate_hz);
  std::string truth_refusal;
  runtime::UnpacedClock clock;
  runtime::TickDriver driver(source, rate_hz);
  TimeUs first_tick_us = 0;
  std::size_t next_known = 0;
  *run = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    if (k == 0 && truth) truth_refusal = truth->check_time_base(t, tick_period_us);
    if (!truth_refusal.empty()) return;
    if (k == 0) first_tick_us = t;
    while (next_known < known_masses.size() &&
           from_seconds(known_masses[next_known].time_s) <= t - first_tick_us) {
      // Checked against the band when parsed: the pipeline takes it at this tick.
      step.declare_known_mass(known_masses[next_known].mass_kg, known_masses[next_known].std_kg);
      ++next_known;
    }
    const runtime::TickRecord& record = step.tick(k, t, source);
    summary->add(record.estimate);
    summary->add_events(record.events);
    if (sink) sink(record.estimate);
  });
  return truth_refusal;
}

std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           const std::vector<KnownMassEvent>& known_masses,
                           scoring::ReplaySummary* summary, EstimateCsvWriter* writer,
                           runtime::TickRun* run) {
  EstimateSink sink;
  if (writer) sink = [writer](const Estimate& e) { writer->write(e); };
  return play_recording(source, step, truth, known_masses, summary, sink, run);
}

}  // namespace vmass
