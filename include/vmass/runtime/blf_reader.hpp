// BlfReader: the CAN frames of a Vector BLF log (binary logging format), read natively with
// zlib, as python-can's BLFReader reads them (can/io/blf.py is the reference of the layout):
//
//   file header     "LOGG", its size (144), ..., file size, object count, start time
//                   (SYSTEMTIME, UTC, milliseconds)
//   objects         "LOBJ", header size, header version, object size, object type, then
//                   header v1 (flags, client index, object version, time stamp) or v2 (flags,
//                   time stamp status, object version, time stamp, original time stamp); the
//                   time stamp counts 10 us when flags is 1, else ns, from the start time
//   LOG_CONTAINER   (10) zlib-compressed (method 2) or stored (0) data holding further objects;
//                   an object may go on in the next container
//   frames          CAN_MESSAGE (1), CAN_MESSAGE2 (86), CAN_FD_MESSAGE (100),
//                   CAN_FD_MESSAGE_64 (101), CAN_ERROR_EXT (73, an error frame)
//
// Every other object is skipped and counted (objects_without_frame()). A frame is what
// vmass-log-convert made of python-can's message: the same time (start + offset rounded to the
// microsecond), id, flags, data; BLF channel N is interface can<N-1> (channel 0 is can0).
//
// Damage is reported, never fatal, and costs a bounded amount: next() gives each object, each
// frame that cannot be a CAN frame (an 11-bit id above 7FF, a CAN FD length of 9) and each damage
// (a truncated file, an object size no object has, bad zlib data, bytes where an object should
// start) as one record: kCorrupt with why, located by file offset (inside a container: the
// container's file offset and the byte of its inflated data). After damage the reader looks for
// the next object signature and goes on: the frames before the damage and those after the next
// intact object are read. A zlib container's frames are given once its stream has ended and
// zlib's check holds (a container whose data fails it gives none: no frame of garbage); only a
// file cut inside a container gives the frames of what its bytes there inflate to, as
// python-can does. Nothing is allocated from a size in the file: the reader holds 64 KiB of the
// file and one container's data (256 KiB, grown up to Limits::max_inflated_bytes for a larger
// container, which is where a container stops), and reads every byte of the file once.
//
// Thread-safety: one reading thread; the stream is kept by reference and read from its current
// position (the file's first byte) on, sequentially.
#pragma once

#include <array>
#include <cstdint>
#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "vmass/can/can_frame.hpp"

namespace vmass::runtime {

class BlfReader {
 public:
  /// Bounds on what a file may claim; an object beyond them is corrupt.
  struct Limits {
    std::uint32_t max_file_header_bytes = 64u << 10;  ///< the file header (writers use 144)
    std::uint32_t max_container_bytes = 64u << 20;    ///< a LOG_CONTAINER's object size
    std::uint32_t max_inflated_bytes = 16u << 20;     ///< a container's data (writers: 128 KiB)
    std::uint32_t max_object_bytes = 16u << 20;       ///< any other object
    std::uint32_t max_frame_object_bytes = 4096;      ///< a frame object (at most ~200 bytes)
  };

  enum class Next : std::uint8_t {
    kFrame,    ///< *record holds a frame
    kNoFrame,  ///< an object of another type, skipped
    kCorrupt,  ///< *why says what and where
    kEnd,      ///< the end of the file, or a read error (read_error())
  };

  struct Record {
    can::CanFrame frame;
    std::uint16_t channel = 0;  ///< BLF's channel, numbered from 1
  };

  explicit BlfReader(std::istream& in);
  BlfReader(std::istream& in, const Limits& limits);
  ~BlfReader();
  BlfReader(const BlfReader&) = delete;
  BlfReader& operator=(const BlfReader&) = delete;

  /// The next record (see the header comment); *why is set for kCorrupt.
  Next next(Record* record, std::string* why);
  /// The number of the record next() returned last, from 1: the objects in file order (the
  /// containers' inner objects, not the containers) and the damages between them.
  std::int64_t record_number() const { return record_number_; }
  /// "" at a clean end of the stream, else the system's reason of the read error.
  const std::string& read_error() const;
  /// Objects skipped as carrying no frame, by object type (types above 255 counted at 256).
  std::uint64_t objects_without_frame(std::uint32_t type) const;
  /// The bytes of the reader's buffers (zlib's state aside): 64 KiB + 256 KiB, more only for a
  /// container of more than 192 KiB of data, never more than 64 KiB + max_inflated_bytes +
  /// max_frame_object_bytes + 64 KiB.
  std::size_t buffer_bytes() const;
  /// "CAN_MESSAGE" for 1, ..., "object type N" for types the reader does not name.
  static std::string object_type_name(std::uint32_t type);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
  std::int64_t record_number_ = 0;
};

/// The interface name of BLF channel `channel`: "can<channel-1>", "can0" for channel 0.
std::string blf_interface_name(std::uint16_t channel);

}  // namespace vmass::runtime
