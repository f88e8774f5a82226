// ParamCheck: collects parameter violations into one message that names each key and bound,
// e.g. "vehicle.wheelbase_m must be > 0, got -1". Used by every params struct's validate().
// Runs at configuration time only (it allocates). Not thread-safe.
#pragma once

#include <string>

namespace vmass {

class ParamCheck {
 public:
  explicit ParamCheck(std::string prefix) : prefix_(std::move(prefix)) {}

  void finite(const std::string& key, double v);
  void positive(const std::string& key, double v);
  void positive_or_inf(const std::string& key, double v);
  void non_negative(const std::string& key, double v);
  void in_open_range(const std::string& key, double v, double lo, double hi);
  /// lo < v <= hi
  void in_half_open_range(const std::string& key, double v, double lo, double hi);
  void at_least(const std::string& key, double v, double lo);
  /// Add a violation described by `what` ("must be ..., got ...").
  void fail(const std::string& key, const std::string& what);
  /// Prepend a nested struct's message ("" when valid).
  void nested(const std::string& message);

  /// "" when valid; else the violations, separated by "; ".
  const std::string& message() const { return message_; }

 private:
  std::string prefix_;
  std::string message_;
};

}  // namespace vmass
