#include "vmass/csv/estimate_csv.hpp"

#include <charconv>
#include <cstring>

#include "vmass/csv/fixed_decimal.hpp"

namespace vmass {
namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;
static_assert(kBufferBytes > EstimateCsvWriter::kMaxRowChars + 1, "a row and its newline fit");

char* put_text(char* p, std::string_view text) {
  std::memcpy(p, text.data(), text.size());
  return p + text.size();
}

/// A number with `decimals` digits (room: kMaxFixedChars), then a comma.
char* put_number(char* p, double v, int decimals) {
  p = write_fixed(p, p + kMaxFixedChars, v, decimals);
  *p++ = ',';
  return p;
}

char* put_count(char* p, long v) {
  p = std::to_chars(p, p + 24, v).ptr;
  *p++ = ',';
  return p;
}

}  // namespace

EstimateCsvWriter::EstimateCsvWriter(const std::string& path) : buffer_(new char[kBufferBytes]) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ && std::fputs((header() + "\n").c_str(), file_) < 0) failed_ = true;
}

EstimateCsvWriter::~EstimateCsvWriter() { close(); }

std::string EstimateCsvWriter::header() {
  return "time_s,mass_kg,mass_ci_low_kg,mass_ci_high_kg,mu_n,status,mass_std_kg,reason,"
         "longitudinal_pairs,lateral_pairs,longitudinal_availability,lateral_availability,"
         "initial_mass_kg";
}

char* EstimateCsvWriter::format_row(const Estimate& e, char* p) {
  // Before the first estimate (no prior yet) the belief cells are empty: a 0 there would read
  // as an estimate of 0 kg.
  const bool mass = e.has_mass();
  p = put_number(p, to_seconds(e.time_us), 2);
  if (mass) {
    for (const double v : {e.mass_kg, e.ci_low_kg, e.ci_high_kg, e.mu_n}) p = put_number(p, v, 3);
  } else {
    p = put_text(p, ",,,,");
  }
  p = put_text(p, status_name(e.status));
  *p++ = ',';
  p = mass ? put_number(p, e.mass_std_kg, 3) : put_text(p, ",");
  p = put_text(p, reason_name(e.reason));
  *p++ = ',';
  p = put_count(p, e.blocks[0].accepted);
  p = put_count(p, e.blocks[1].accepted);
  p = put_number(p, e.blocks[0].availability(), 5);
  p = put_number(p, e.blocks[1].availability(), 5);
  if (mass) return write_fixed(p, p + kMaxFixedChars, e.initial_mass_kg, 3);
  return p;
}

std::string EstimateCsvWriter::row(const Estimate& e) {
  std::string s(kMaxRowChars, '\0');
  s.resize(static_cast<std::size_t>(format_row(e, s.data()) - s.data()));
  return s;
}

void EstimateCsvWriter::write(const Estimate& e) {
  if (!file_) return;
  if (kBufferBytes - used_ < kMaxRowChars + 1) flush_buffer();
  char* end = format_row(e, buffer_.get() + used_);
  *end++ = '\n';
  used_ = static_cast<std::size_t>(end - buffer_.get());
}

void EstimateCsvWriter::flush_buffer() {
  if (used_ > 0 && std::fwrite(buffer_.get(), 1, used_, file_) != used_) failed_ = true;
  used_ = 0;
}

bool EstimateCsvWriter::close() {
  if (!file_) return !failed_;
  flush_buffer();
  if (std::fclose(file_) != 0) failed_ = true;
  file_ = nullptr;
  return !failed_;
}

}  // namespace vmass
