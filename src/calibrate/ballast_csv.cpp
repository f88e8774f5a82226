#include "vmass/calibrate/ballast_csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "vmass/io/regular_file.hpp"

namespace vmass::calibrate {
namespace {

struct UnitFactor {
  const char* unit;
  double factor;
};

constexpr UnitFactor kMassUnits[] = {{"kg", 1.0}, {"t", 1000.0}, {"lb", 0.45359237}};
constexpr UnitFactor kDeflectionUnits[] = {
    {"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}, {"in", 0.0254}};
constexpr UnitFactor kTimeUnits[] = {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}};
constexpr UnitFactor kSpeedUnits[] = {{"mps", 1.0}, {"kmh", 1.0 / 3.6}};

/// The range a physical quantity of a static ballast test can take, in SI units. A value beyond
/// it is a unit or typing error (grams in a _kg column, millimetres in an _m column) that would
/// otherwise fit an absurd stiffness without complaint.
struct Bound {
  double low;
  double high;
  const char* unit;
  const char* why;
};

// Ballast is added to (or, below zero, taken from) one road vehicle: the heaviest trucks weigh
// about 60 t in all. The config loader's own limit on a _kg key (1e7 kg, yaml_reader.cpp) bounds
// any mass it reads, not ballast, so it is too loose to catch a unit error here.
constexpr Bound kAddedMassBound{-1000.0, 100000.0, "kg", "ballast added to one vehicle"};
// A suspension travels well under 0.5 m; 1 m leaves room for a sensor's zero offset while still
// catching millimetres written in an _m column (the loader's 1e4 m bounds any length key).
constexpr Bound kDeflectionBound{-1.0, 1.0, "m", "a suspension travels well under 0.5 m"};

// A number for a message, 6 significant digits (the tools keep the "C" numeric locale).
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// "" when v is within b, else "V UNIT is outside [LOW, HIGH] UNIT (WHY; a unit error?)".
std::string out_of_bound(double v, const Bound& b) {
  if (v >= b.low && v <= b.high) return "";
  return number_text(v) + " " + b.unit + " is outside [" + number_text(b.low) + ", " +
         number_text(b.high) + "] " + b.unit + " (" + b.why + "; a unit error?)";
}

template <std::size_t N>
std::string unit_list(const UnitFactor (&units)[N]) {
  std::string s;
  for (const UnitFactor& u : units) s += (s.empty() ? "" : ", ") + std::string(u.unit);
  return s;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// Locale-free strict number: the whole cell must be consumed.
bool parse_number(std::string_view cell, double* out) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  if (cell.empty()) return false;
  const char* end = cell.data() + cell.size();
  const auto [ptr, ec] = std::from_chars(cell.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

struct Column {
  int index = -1;
  double factor = 1.0;
  std::string name;
};

class Failure {
 public:
  explicit Failure(std::string message) : message_(std::move(message)) {}
  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

// Matches `prefix_<unit>`; throws Failure for a missing or unknown unit.
template <std::size_t N>
bool match_column(std::string_view name, const std::string& prefix, const UnitFactor (&units)[N],
                  const std::string& where, int index, Column* column) {
  if (name == prefix) {
    throw Failure(where + ": column '" + std::string(name) + "' has no unit (expected " + prefix +
                  "_<unit>, unit one of " + unit_list(units) + ")");
  }
  if (name.size() <= prefix.size() + 1 || name.substr(0, prefix.size() + 1) != prefix + "_") {
    return false;
  }
  const std::string_view unit = name.substr(prefix.size() + 1);
  for (const UnitFactor& u : units) {
    if (unit == u.unit) {
      if (column->index >= 0) {
        throw Failure(where + ": two " + prefix + " columns ('" + column->name + "' and '" +
                      std::string(name) + "')");
      }
      column->index = index;
      column->factor = u.factor;
      column->name = std::string(name);
      return true;
    }
  }
  throw Failure(where + ": column '" + std::string(name) + "': unknown unit '" + std::string(unit) +
                "' (known: " + unit_list(units) + ")");
}

/// The columns the header names.
struct Columns {
  Column mass, deflection, time, speed;
  std::size_t field_count = 0;  ///< the header's; every row must have as many
};

/// The header: which column is what, in which unit; the file's kind. Throws Failure.
// The header as a message may quote it: cut to 80 characters, and never raw control bytes.
std::string quoted_header(std::string_view line) {
  constexpr std::size_t kMaxShown = 80;
  for (const char ch : line) {
    const auto byte = static_cast<unsigned char>(ch);
    if ((byte < 0x20 && ch != '\t') || byte == 0x7f) return "(binary data: not a CSV header)";
  }
  if (line.size() <= kMaxShown) return "'" + std::string(line) + "'";
  return "'" + std::string(line.substr(0, kMaxShown)) + "...'";
}

Columns read_header(const std::vector<std::string_view>& cells, std::string_view line,
                    const std::string& where, BallastCsvKind* kind) {
  Columns c;
  c.field_count = cells.size();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const int idx = static_cast<int>(i);
    if (match_column(cells[i], "added_mass", kMassUnits, where, idx, &c.mass)) continue;
    if (match_column(cells[i], "rear_right_deflection", kDeflectionUnits, where, idx,
                     &c.deflection)) {
      continue;
    }
    if (match_column(cells[i], "time", kTimeUnits, where, idx, &c.time)) continue;
    if (match_column(cells[i], "speed", kSpeedUnits, where, idx, &c.speed)) continue;
  }
  if (c.deflection.index < 0) {
    throw Failure(where + ": no rear_right_deflection_<unit> column (unit one of " +
                  unit_list(kDeflectionUnits) + ") in the header " + quoted_header(line));
  }
  if (c.mass.index < 0 && c.time.index < 0) {
    throw Failure(where +
                  ": need an added_mass_<unit> column (one row per sample or step) "
                  "or a time_<unit> column (a recording for plateau detection); header " +
                  quoted_header(line));
  }
  *kind = c.mass.index >= 0 ? BallastCsvKind::kSteps : BallastCsvKind::kSeries;
  return c;
}

/// A data row's cells as SI numbers. An empty cell gives NaN when allowed; anything else must
/// be a finite number. Throws Failure naming the file, line and column.
class RowReader {
 public:
  RowReader(const std::vector<std::string_view>& cells, const std::string& where)
      : cells_(cells), where_(where) {}

  /// The cell in SI units; `bound`, when given, is checked on it.
  double value(const Column& c, bool empty_allowed, const Bound* bound = nullptr) const {
    const std::string_view cell = cells_[static_cast<std::size_t>(c.index)];
    if (cell.empty()) {
      if (empty_allowed) return std::nan("");
      throw Failure(where_ + ": " + c.name + ": empty cell");
    }
    double v = 0.0;
    if (!parse_number(cell, &v)) {
      throw Failure(where_ + ": " + c.name + ": '" + std::string(cell) +
                    "' is not a number (units belong in the column name)");
    }
    if (std::isnan(v)) throw Failure(where_ + ": " + c.name + ": NaN");
    if (!std::isfinite(v)) throw Failure(where_ + ": " + c.name + ": infinite value");
    const double si = v * c.factor;
    if (bound != nullptr) {
      if (const std::string m = out_of_bound(si, *bound); !m.empty()) {
        throw Failure(where_ + ": " + c.name + ": " + m);
      }
    }
    return si;
  }

 private:
  const std::vector<std::string_view>& cells_;
  const std::string& where_;
};

/// A row must have the header's field count. One more is most often a decimal comma ("13,3" for
/// 13.3) splitting a number in two, which would read 13 and shift the columns after it; one
/// fewer is a row cut short, whose cells may sit under the wrong column. Throws Failure.
void check_field_count(std::size_t fields, std::size_t header_fields, const std::string& where) {
  if (fields == header_fields) return;
  const std::string counts = std::to_string(fields) + (fields == 1 ? " field" : " fields") +
                             ", the header has " + std::to_string(header_fields);
  throw Failure(where + ": " + counts +
                (fields > header_fields ? "; decimal commas? (write 13.3, not 13,3)"
                                        : "; a row cut short? (an empty cell keeps its comma)"));
}

/// One data row into the steps or the series (a series row without time or deflection is
/// skipped, counted).
void read_row(const RowReader& row, const Columns& c, BallastCsv* csv) {
  if (csv->kind == BallastCsvKind::kSteps) {
    BallastSample s;
    s.added_mass_kg = row.value(c.mass, false, &kAddedMassBound);
    s.deflection_m = row.value(c.deflection, false, &kDeflectionBound);
    csv->samples.push_back(s);
    return;
  }
  DeflectionPoint p;
  p.time_s = row.value(c.time, true);
  p.deflection_m = row.value(c.deflection, true, &kDeflectionBound);
  if (c.speed.index >= 0) p.speed_mps = row.value(c.speed, true);
  if (std::isnan(p.time_s) || std::isnan(p.deflection_m)) {
    ++csv->skipped_rows;
    return;
  }
  csv->series.push_back(p);
}

// Spreadsheets (Excel's "CSV UTF-8") start the file with a UTF-8 byte order mark: it belongs to
// no column name, so it is dropped rather than refused.
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// The --masses list is held to the same bound as an added_mass column.
std::string check_mass_list(const std::vector<double>& masses_kg) {
  for (const double m : masses_kg) {
    if (std::string why = out_of_bound(m, kAddedMassBound); !why.empty()) return "masses: " + why;
  }
  return "";
}

BallastCsv parse(std::string_view text, const std::string& name) {
  if (text.substr(0, kUtf8Bom.size()) == kUtf8Bom) text.remove_prefix(kUtf8Bom.size());
  BallastCsv csv;
  Columns columns;
  bool have_header = false;
  std::size_t pos = 0;
  long line_number = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view raw =
        text.substr(pos, nl == std::string_view::npos ? text.npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_number;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const std::string where = name + ":" + std::to_string(line_number);
    const std::vector<std::string_view> cells = split(line);
    if (!have_header) {
      have_header = true;
      columns = read_header(cells, line, where, &csv.kind);
      continue;
    }
    check_field_count(cells.size(), columns.field_count, where);
    read_row(RowReader(cells, where), columns, &csv);
  }
  if (!have_header) throw Failure(name + ": empty file (no header)");
  if (csv.kind == BallastCsvKind::kSteps ? csv.samples.empty() : csv.series.empty()) {
    throw Failure(name + ": no data rows");
  }
  return csv;
}

}  // namespace

BallastCsvRead parse_ballast_csv(std::string_view text, const std::string& name) {
  BallastCsvRead out;
  try {
    out.csv = parse(text, name);
  } catch (const Failure& f) {
    out.error = f.message();
  }
  return out;
}

BallastCsvRead read_ballast_csv(const std::string& path) {
  const io::FileText file = io::read_regular_file(path, io::kMaxTableBytes, "ballast CSV");
  if (!file.ok()) {
    BallastCsvRead out;
    out.error = file.error;
    return out;
  }
  return parse_ballast_csv(file.text, path);
}

std::string parse_mass_list(const std::string& text, std::vector<double>* out) {
  out->clear();
  const std::string_view all = trim(text);
  // first:step:last
  if (all.find(':') != std::string_view::npos) {
    std::vector<double> v;
    std::size_t start = 0;
    while (true) {
      const std::size_t colon = all.find(':', start);
      double x = 0.0;
      const std::string_view cell =
          trim(all.substr(start, colon == all.npos ? all.npos : colon - start));
      if (!parse_number(cell, &x) || !std::isfinite(x)) {
        return "masses: '" + std::string(cell) + "' is not a number";
      }
      v.push_back(x);
      if (colon == all.npos) break;
      start = colon + 1;
    }
    if (v.size() != 3 || !(v[1] > 0.0) || v[2] < v[0]) {
      return "masses: a range is FIRST:STEP:LAST with STEP > 0 and LAST >= FIRST, got '" +
             std::string(all) + "'";
    }
    const double count = std::floor((v[2] - v[0]) / v[1] + 1e-9);
    if (count > 10000) return "masses: range too long";
    for (int i = 0; i <= static_cast<int>(count); ++i) out->push_back(v[0] + i * v[1]);
    return check_mass_list(*out);
  }
  for (std::string_view cell : split(all)) {
    double x = 0.0;
    if (!parse_number(cell, &x) || !std::isfinite(x)) {
      return "masses: '" + std::string(cell) + "' is not a number (kg)";
    }
    out->push_back(x);
  }
  if (out->empty()) return "masses: empty list";
  return check_mass_list(*out);
}

}  // namespace vmass::calibrate
