#include "vmass/json/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace vmass::json {
namespace {

// The double that printf's text of v reads back as (the C locale's point: the tools keep it).
Json rounded(double v, const char* format, int precision) {
  if (!std::isfinite(v)) return nullptr;
  char buf[400];  // "%.*f" of 1e308 with a few decimals fits
  const int n = std::snprintf(buf, sizeof buf, format, precision, v);
  if (n <= 0 || n >= static_cast<int>(sizeof buf)) return v;  // too long to round: as it is
  double r = v;
  std::from_chars(buf, buf + n, r);
  return r;
}

}  // namespace

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(); }

Json fixed(double v, int decimals) { return rounded(v, "%.*f", decimals); }

Json significant(double v, int digits) { return rounded(v, "%.*g", digits); }

std::string dump(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

}  // namespace vmass::json
