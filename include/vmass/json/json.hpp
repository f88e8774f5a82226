// JSON as vmass writes it: through nlohmann::json (one escaper, one number writer), keys in the
// order they are set (ordered_json), one line. nlohmann writes a double as the shortest text that
// reads back as it; a number shown at a precision (a mass to 3 decimals, 10 significant digits)
// is rounded to it first, so that it reads back as the double its printf text did. Numbers that
// are not finite are null. Thread-safe (pure functions).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace vmass::json {

using Json = nlohmann::ordered_json;

/// v as it is; null when not finite.
Json number(double v);
/// v rounded to `decimals` after the point, as printf("%.*f") rounds; null when not finite.
Json fixed(double v, int decimals);
/// v rounded to `digits` significant digits, as printf("%.*g") rounds; null when not finite.
Json significant(double v, int digits);

/// One line without its newline. Text that is not UTF-8 (a DBC's names in Windows-1252, a file
/// name) is written with U+FFFD in place of the bad bytes instead of being refused.
std::string dump(const Json& j);

}  // namespace vmass::json
