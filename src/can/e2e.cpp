#include "vmass/can/e2e.hpp"

namespace vmass::can {
namespace {

std::uint64_t raw_bits(const Decoder& d, SignalRef ref, const CanFrame& f) {
  const CompiledSignal& s = d.compiled(ref);
  return static_cast<std::uint64_t>(d.extract_raw(s, f.data)) & s.mask;
}

bool checksum_holds(const Decoder& d, const E2eProfile& p, const CanFrame& f) {
  std::uint8_t covered[kFdMaxLen];
  std::size_t n = 0;
  for (int i = 0; i < f.len && i < kFdMaxLen; ++i) {
    if ((p.covered_bytes >> i) & 1u) covered[n++] = f.data[i];
  }
  ChecksumInput in;
  in.bytes = covered;
  in.size = n;
  in.data_id = p.data_id;
  in.has_data_id = p.has_data_id;
  in.bits = d.compiled(p.checksum).length;
  return p.algorithm(in) == raw_bits(d, p.checksum, f);
}

}  // namespace

E2eResult check_e2e(const Decoder& decoder, const E2eProfile& p, const CanFrame& frame, bool resync,
                    E2eState* state) {
  if (p.checksum.valid() && !checksum_holds(decoder, p, frame)) return E2eResult::kChecksumFail;
  if (!p.counter.valid()) return E2eResult::kOk;
  const std::uint64_t c = raw_bits(decoder, p.counter, frame);
  const std::uint64_t mask = decoder.compiled(p.counter).mask;
  const bool first = !state->has_counter || resync;
  const std::uint64_t step = (c - state->last_counter) & mask;  // modulo 2^length
  state->last_counter = c;
  state->has_counter = true;
  if (first) return E2eResult::kOk;
  return step >= 1 && step <= p.max_counter_step ? E2eResult::kOk : E2eResult::kCounterFail;
}

bool MessageValidity::on_frame(bool passed) {
  if (!passed) {
    goods_ = 0;
    if (++failures_ >= invalid_after_) valid_ = false;
    return false;
  }
  failures_ = 0;
  if (!valid_ && ++goods_ >= valid_after_) {
    valid_ = true;
    goods_ = 0;
  }
  return valid_;
}

}  // namespace vmass::can
