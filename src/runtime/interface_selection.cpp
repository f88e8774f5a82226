#include "vmass/runtime/interface_selection.hpp"

#include "vmass/io/excerpt.hpp"

namespace vmass::runtime {
namespace {

bool is_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '.' || c == '-';
}

std::string frames(std::uint64_t n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); }

}  // namespace

std::string InterfaceSelection::name_error(std::string_view name) {
  const std::string rule = "an interface name has 1 to " + std::to_string(kMaxNameBytes) +
                           " characters of A-Z a-z 0-9 _ . - (e.g. can1)";
  if (name.empty()) return "empty: " + rule;
  if (name.size() > kMaxNameBytes) return "'" + io::excerpt(name) + "' is too long: " + rule;
  for (const char c : name) {
    if (!is_name_char(c)) return "'" + io::excerpt(name) + "': " + rule;
  }
  return "";
}

bool InterfaceSelection::take(std::string_view interface) {
  if (interface == name_) return true;
  ++skipped_;
  for (Other& other : others_) {
    if (other.name == interface) {
      ++other.frames;
      return false;
    }
  }
  if (others_.size() < kMaxCountedInterfaces) {
    others_.push_back({std::string(interface), 1});
  } else {
    ++uncounted_;
  }
  return false;
}

std::string InterfaceSelection::none_taken_reason() const {
  std::string reason = "no frame on interface " + name_ + "; the log has ";
  if (others_.empty()) return reason + "no frame";
  for (std::size_t i = 0; i < others_.size(); ++i) {
    if (i > 0) reason += ", ";
    reason += io::excerpt(others_[i].name) + " (" + frames(others_[i].frames) + ")";
  }
  if (uncounted_ > 0) reason += ", and " + frames(uncounted_) + " on more interfaces";
  return reason;
}

}  // namespace vmass::runtime
