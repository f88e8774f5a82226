#include "vmass/service/lcm_url.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <cstdint>
#include <string_view>

namespace vmass::service {
namespace {

/// An integer in [lo, hi] written in full, or false.
bool integer_in(std::string_view text, long lo, long hi) {
  long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() && v >= lo && v <= hi;
}

std::string multicast_error(std::string_view network) {
  const std::size_t colon = network.rfind(':');
  if (colon == std::string_view::npos) return "expected ADDRESS:PORT after udpm://";
  const std::string address(network.substr(0, colon));
  in_addr a{};
  if (inet_pton(AF_INET, address.c_str(), &a) != 1) {
    return "'" + address + "' is not an IPv4 address";
  }
  const std::uint32_t host = ntohl(a.s_addr);
  if ((host >> 28) != 0xE) return address + " is not a multicast address (224.0.0.0/4)";
  if (!integer_in(network.substr(colon + 1), 1, 65535)) return "port must be 1..65535";
  return "";
}

std::string udpm_option_error(std::string_view key, std::string_view value) {
  if (key == "ttl") return integer_in(value, 0, 255) ? "" : "ttl must be an integer 0..255";
  if (key == "recv_buf_size") {
    return integer_in(value, 1, 1L << 31) ? "" : "recv_buf_size must be a positive integer";
  }
  return "unknown option '" + std::string(key) + "' (udpm takes ttl, recv_buf_size)";
}

std::string file_option_error(std::string_view key, std::string_view value) {
  if (key == "mode") {
    return value == "r" || value == "w" || value == "a" ? "" : "mode must be r, w or a";
  }
  if (key == "speed" || key == "start_timestamp") return "";  // liblcm parses these itself
  return "unknown option '" + std::string(key) + "' (file takes mode, speed, start_timestamp)";
}

/// Each KEY=VALUE of the query through `check`.
template <class Check>
std::string options_error(std::string_view query, Check check) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) return "option '" + std::string(item) + "' has no '='";
    const std::string e = check(item.substr(0, eq), item.substr(eq + 1));
    if (!e.empty()) return e;
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return "";
}

}  // namespace

std::string lcm_url_error(const std::string& url) {
  const std::string_view u(url);
  const std::size_t sep = u.find("://");
  if (sep == std::string_view::npos) return "expected PROVIDER://NETWORK (e.g. udpm://...)";
  const std::string_view provider = u.substr(0, sep);
  const std::string_view rest = u.substr(sep + 3);
  const std::size_t q = rest.find('?');
  const std::string_view network = rest.substr(0, q);
  const std::string_view query = q == std::string_view::npos ? "" : rest.substr(q + 1);
  if (provider == "udpm" || provider == "mpudpm") {
    const std::string e = network.empty() ? "" : multicast_error(network);  // "": liblcm's default
    return e.empty() ? options_error(query, udpm_option_error) : e;
  }
  if (provider == "file") {
    if (network.empty()) return "file:// needs a path";
    return options_error(query, file_option_error);
  }
  if (provider == "memq" || provider == "tcpq") return "";
  return "unknown LCM provider '" + std::string(provider) + "' (udpm, mpudpm, file, memq, tcpq)";
}

}  // namespace vmass::service
