// A BLF writer for the tests of the BLF reader: each object laid out byte by byte as the format
// has it (python-can's blf.py and Vector's binlog_objects.h agree on it), so that a test can
// build what no writer at hand writes: header version 2, 10 us time stamps, CAN_MESSAGE2,
// CAN_FD_MESSAGE_64 with extension data, unknown objects, objects that go on in the next
// container, stored and zlib containers, and any damage.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vmass::runtime::blftest {

inline std::string le(std::uint64_t v, int bytes) {
  std::string s;
  for (int i = 0; i < bytes; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
  return s;
}

inline std::string bytes(const std::vector<int>& v, std::size_t size) {
  std::string s(size, '\0');
  for (std::size_t i = 0; i < v.size() && i < size; ++i) s[i] = static_cast<char>(v[i]);
  return s;
}

/// An object: "LOBJ", header size, version, object size, type, header v1 (flags, client index,
/// object version, time stamp) or v2 (flags, time stamp status, reserved, object version, time
/// stamp, original time stamp), its fields, padded with size % 4 zeros.
inline std::string object(std::uint32_t type, const std::string& fields, std::uint64_t stamp,
                          std::uint32_t flags = 2, std::uint16_t version = 1) {
  const std::size_t header = version == 2 ? 40 : 32;
  const std::size_t size = header + fields.size();
  std::string o = "LOBJ" + le(header, 2) + le(version, 2) + le(size, 4) + le(type, 4);
  if (version == 2) {
    o += le(flags, 4) + le(0, 1) + le(0, 1) + le(0, 2) + le(stamp, 8) + le(0, 8);
  } else {
    o += le(flags, 4) + le(0, 2) + le(0, 2) + le(stamp, 8);
  }
  return o + fields + std::string(size % 4, '\0');
}

/// CAN_MESSAGE (1) or CAN_MESSAGE2 (86) fields: channel, flags (0x80 remote), dlc, id (bit 31:
/// extended), 8 data bytes (CAN_MESSAGE2: then frame length, bit count, reserved).
inline std::string can_message_fields(std::uint16_t channel, std::uint32_t id,
                                      const std::vector<int>& data, int dlc = -1,
                                      std::uint8_t flags = 0, bool message2 = false) {
  std::string f = le(channel, 2) + le(flags, 1) +
                  le(dlc < 0 ? data.size() : static_cast<std::size_t>(dlc), 1) + le(id, 4) +
                  bytes(data, 8);
  if (message2) f += le(1234, 4) + le(111, 1) + le(0, 1) + le(0, 2);
  return f;
}

/// CAN_FD_MESSAGE (100) fields: channel, flags, dlc, id, frame length, bit count, FD flags
/// (1 EDL, 2 BRS, 4 ESI), valid data bytes, 5 reserved, 64 data bytes.
inline std::string can_fd_fields(std::uint16_t channel, std::uint32_t id,
                                 const std::vector<int>& data, int dlc, std::uint8_t fd_flags,
                                 int valid = -1, std::uint8_t flags = 0) {
  return le(channel, 2) + le(flags, 1) + le(dlc, 1) + le(id, 4) + le(0, 4) + le(0, 1) +
         le(fd_flags, 1) + le(valid < 0 ? data.size() : static_cast<std::size_t>(valid), 1) +
         std::string(5, '\0') + bytes(data, 64);
}

/// CAN_FD_MESSAGE_64 (101) fields: channel (1 byte), dlc, valid bytes, tx count, id, frame
/// length, flags (0x10 remote, 0x1000 EDL, 0x2000 BRS, 0x4000 ESI), two bit rates, two time
/// offsets, bit count, direction, ext data offset, crc; then the data (`present` bytes of it).
inline std::string can_fd64_fields(std::uint8_t channel, std::uint32_t id,
                                   const std::vector<int>& data, int dlc, std::uint32_t flags,
                                   std::uint8_t ext_offset = 0, int present = -1) {
  const std::size_t n = present < 0 ? data.size() : static_cast<std::size_t>(present);
  return le(channel, 1) + le(dlc, 1) + le(data.size(), 1) + le(0, 1) + le(id, 4) + le(0, 4) +
         le(flags, 4) + le(0, 4) + le(0, 4) + le(0, 4) + le(0, 4) + le(0, 2) + le(0, 1) +
         le(ext_offset, 1) + le(0, 4) + bytes(data, n);
}

/// CAN_ERROR_EXT (73) fields: channel, length, flags, ecc, position, dlc, reserved, frame
/// length, id, ext flags, reserved, 8 data bytes.
inline std::string error_ext_fields(std::uint16_t channel, std::uint32_t id,
                                    const std::vector<int>& data) {
  return le(channel, 2) + le(0, 2) + le(0, 4) + le(0, 1) + le(0, 1) + le(data.size(), 1) +
         le(0, 1) + le(0, 4) + le(id, 4) + le(0, 2) + le(0, 2) + bytes(data, 8);
}

/// A LOG_CONTAINER (10) holding `data`, zlib-compressed or stored, padded with size % 4 zeros.
inline std::string container(const std::string& data, bool compress) {
  std::string payload = data;
  if (compress) {
    uLongf n = compressBound(static_cast<uLong>(data.size()));
    payload.assign(n, '\0');
    if (compress2(reinterpret_cast<Bytef*>(payload.data()), &n,
                  reinterpret_cast<const Bytef*>(data.data()), static_cast<uLong>(data.size()),
                  Z_DEFAULT_COMPRESSION) != Z_OK) {
      throw std::runtime_error("compress2 failed");
    }
    payload.resize(n);
  }
  const std::size_t size = 32 + payload.size();
  return "LOBJ" + le(16, 2) + le(1, 2) + le(size, 4) + le(10, 4) + le(compress ? 2 : 0, 2) +
         std::string(6, '\0') + le(data.size(), 4) + std::string(4, '\0') + payload +
         std::string(size % 4, '\0');
}

struct SystemTime {
  int year = 2021, month = 6, day_of_week = 2, day = 1, hour = 8, minute = 0, second = 0, ms = 0;
};

/// The file header (144 bytes): "LOGG", its size, application and BLF versions, file size,
/// uncompressed size, object count, objects read, start and stop time.
inline std::string file_header(std::uint64_t file_size, std::uint32_t objects,
                               const SystemTime& start) {
  const auto time = [](const SystemTime& t) {
    return le(t.year, 2) + le(t.month, 2) + le(t.day_of_week, 2) + le(t.day, 2) + le(t.hour, 2) +
           le(t.minute, 2) + le(t.second, 2) + le(t.ms, 2);
  };
  std::string h = "LOGG" + le(144, 4) + std::string("\x05\x00\x00\x00\x02\x06\x08\x01", 8) +
                  le(file_size, 8) + le(file_size, 8) + le(objects, 4) + le(0, 4) + time(start) +
                  time(start);
  return h + std::string(144 - h.size(), '\0');
}

/// A whole file: the inner objects cut into containers of `container_bytes` of data each (an
/// object may go on in the next), then `after` (objects outside any container).
struct Built {
  std::string file;
  /// Per container: its first byte in the file, its end, and where its data begins in the
  /// concatenated data.
  struct Container {
    std::size_t begin, end, data_begin;
  };
  std::vector<Container> containers;
};

inline Built build(const std::string& inner, std::size_t container_bytes, bool compress,
                   const SystemTime& start = {}, const std::string& after = {},
                   std::uint32_t objects = 0) {
  Built b;
  std::string body;
  for (std::size_t at = 0; at < inner.size(); at += container_bytes) {
    const std::size_t begin = 144 + body.size();
    body += container(inner.substr(at, container_bytes), compress);
    b.containers.push_back({begin, 144 + body.size(), at});
  }
  body += after;
  b.file = file_header(144 + body.size(), objects, start) + body;
  return b;
}

}  // namespace vmass::runtime::blftest
