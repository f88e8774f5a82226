#include "replay_run.hpp"

namespace vmass {

std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           scoring::ReplaySummary* summary, EstimateCsvWriter* writer,
                           runtime::TickRun* run) {
  const double rate_hz = step.pipeline().params().estimator.differencing.tick_rate_hz;
  const TimeUs tick_period_us = from_seconds(1.0 / rate_hz);
  std::string truth_refusal;
  runtime::UnpacedClock clock;
  runtime::TickDriver driver(source, rate_hz);
  *run = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    if (k == 0 && truth) truth_refusal = truth->check_time_base(t, tick_period_us);
    if (!truth_refusal.empty()) return;
    const runtime::TickRecord& record = step.tick(k, t, source);
    summary->add(record.estimate);
    summary->add_events(record.events);
    if (writer) writer->write(record.estimate);
  });
  return truth_refusal;
}

}  // namespace vmass
