#include "vmass/core/param_check.hpp"

#include <cmath>
#include <sstream>

namespace vmass {
namespace {
std::string number(double v) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << v;
  return s.str();
}
}  // namespace

void ParamCheck::fail(const std::string& key, const std::string& what) {
  if (!message_.empty()) message_ += "; ";
  message_ += prefix_.empty() ? key : prefix_ + "." + key;
  message_ += " " + what;
}

void ParamCheck::nested(const std::string& message) {
  if (message.empty()) return;
  if (!message_.empty()) message_ += "; ";
  message_ += message;
}

void ParamCheck::finite(const std::string& key, double v) {
  if (!std::isfinite(v)) fail(key, "must be a finite number, got " + number(v));
}
void ParamCheck::positive(const std::string& key, double v) {
  if (!(std::isfinite(v) && v > 0.0)) fail(key, "must be > 0, got " + number(v));
}
void ParamCheck::positive_or_inf(const std::string& key, double v) {
  if (!(v > 0.0)) fail(key, "must be > 0 (or .inf), got " + number(v));
}
void ParamCheck::non_negative(const std::string& key, double v) {
  if (!(std::isfinite(v) && v >= 0.0)) fail(key, "must be >= 0, got " + number(v));
}
void ParamCheck::in_open_range(const std::string& key, double v, double lo, double hi) {
  if (!(v > lo && v < hi)) {
    fail(key, "must be in (" + number(lo) + ", " + number(hi) + "), got " + number(v));
  }
}
void ParamCheck::in_half_open_range(const std::string& key, double v, double lo, double hi) {
  if (!(v > lo && v <= hi)) {
    fail(key, "must be in (" + number(lo) + ", " + number(hi) + "], got " + number(v));
  }
}
void ParamCheck::at_least(const std::string& key, double v, double lo) {
  if (!(std::isfinite(v) && v >= lo)) fail(key, "must be >= " + number(lo) + ", got " + number(v));
}

}  // namespace vmass
