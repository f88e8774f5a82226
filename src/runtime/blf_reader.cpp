// Vector BLF read natively (see include/vmass/runtime/blf_reader.hpp).
//
// Two buffered streams: the file (file_: the file header, the top-level objects, the
// containers' compressed bytes) and the containers' data (data_: what they inflate to, one
// stream across containers, since an object may go on in the next one). Each is a fixed
// buffer; a size read from the file is only ever compared, never allocated. Damage in a
// container puts a cut at the end of the data inflated so far: the whole objects before it are
// read, an object that reaches over it is dropped, and after it the reader looks for the next
// object signature quietly (the damage was reported once).
#include "vmass/runtime/blf_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <ios>
#include <limits>
#include <new>
#include <system_error>
#include <utility>
#include <vector>

#include "vmass/io/stream_failure.hpp"

namespace vmass::runtime {
namespace {

constexpr std::uint32_t kCanMessage = 1;
constexpr std::uint32_t kLogContainer = 10;
constexpr std::uint32_t kCanErrorExt = 73;
constexpr std::uint32_t kCanMessage2 = 86;
constexpr std::uint32_t kCanFdMessage = 100;
constexpr std::uint32_t kCanFdMessage64 = 101;

constexpr std::size_t kFileHeaderFields = 72;  ///< the fields of the file header read
constexpr std::size_t kBaseHeader = 16;        ///< "LOBJ", header size, version, size, type
constexpr std::size_t kContainerHeader = 32;   ///< base header, method, uncompressed size
constexpr std::size_t kFileBufferBytes = 64u << 10;
constexpr std::size_t kDataBufferBytes = 256u << 10;
constexpr std::size_t kInflateChunk = 64u << 10;
constexpr std::size_t kPaddingWindow = 4;  ///< bytes of padding tolerated before a signature
constexpr std::uint64_t kNoCut = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint32_t kExtendedIdBit = 0x80000000u;
constexpr double kTwoTo53 = 9007199254740992.0;
/// |time| beyond this is no log's (and would overflow microseconds in an int64 at 10 us units).
constexpr double kMaxAbsTimeS = 1e12;

std::uint16_t le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (static_cast<unsigned>(p[1]) << 8));
}
std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
std::uint64_t le64(const std::uint8_t* p) {
  return static_cast<std::uint64_t>(le32(p)) | (static_cast<std::uint64_t>(le32(p + 4)) << 32);
}

/// Where "LOBJ" starts in [p, p + n), or n when it does not start there (wholly).
std::size_t find_signature(const std::uint8_t* p, std::size_t n) {
  std::size_t at = 0;
  while (n >= 4 && at + 4 <= n) {
    const void* l = std::memchr(p + at, 'L', n - 3 - at);
    if (l == nullptr) return n;
    at = static_cast<std::size_t>(static_cast<const std::uint8_t*>(l) - p);
    if (std::memcmp(p + at, "LOBJ", 4) == 0) return at;
    ++at;
  }
  return n;
}

struct ObjectHeader {
  std::uint16_t header_size = 0;
  std::uint16_t version = 0;
  std::uint32_t size = 0;
  std::uint32_t type = 0;
};

ObjectHeader parse_header(const std::uint8_t* o) {
  return {le16(o + 4), le16(o + 6), le32(o + 8), le32(o + 12)};
}

/// The object header's size for a header version (1: 32 bytes, 2: 40), 0 for another.
std::size_t full_header_size(std::uint16_t version) {
  return version == 1 ? 32 : version == 2 ? 40 : 0;
}

bool is_frame_type(std::uint32_t type) {
  return type == kCanMessage || type == kCanMessage2 || type == kCanErrorExt ||
         type == kCanFdMessage || type == kCanFdMessage64;
}

/// The bytes of a frame object's fields after its header (what python-can unpacks).
std::size_t frame_fields_size(std::uint32_t type) {
  switch (type) {
    case kCanMessage:
    case kCanMessage2:
      return 16;  // channel, flags, dlc, id, data[8]
    case kCanErrorExt:
      return 32;  // channel, length, flags, ecc, position, dlc, frame length, id, ext flags, data
    case kCanFdMessage:
      return 84;  // channel, flags, dlc, id, frame length, bit count, FD flags, valid, data[64]
    case kCanFdMessage64:
      return 40;  // channel, dlc, valid, tx count, id, ..., flags, ..., direction, ext offset, crc
    default:
      return 0;
  }
}

std::string bytes_text(std::uint64_t n) {
  return std::to_string(n) + (n == 1 ? " byte" : " bytes");
}

/// mantissa x 10^-exponent, correctly rounded (Python's float(Decimal(mantissa) * 1e-exponent)).
double scaled_decimal(std::int64_t mantissa, int exponent) {
  const double pow10 = exponent == 5 ? 1e5 : exponent == 6 ? 1e6 : 1e9;
  if (std::fabs(static_cast<double>(mantissa)) < kTwoTo53) {
    return static_cast<double>(mantissa) / pow10;  // both exact: one correctly rounded division
  }
  char text[48];
  std::snprintf(text, sizeof text, "%llde-%d", static_cast<long long>(mantissa), exponent);
  return std::strtod(text, nullptr);  // correctly rounded; no decimal point, no locale
}

/// An object's time offset in seconds: 10 us units when flags is 1, else ns (as python-can).
double offset_seconds(std::uint64_t stamp, std::uint32_t flags) {
  const int exponent = flags == 1 ? 5 : 9;
  if (stamp < (1ull << 53)) return scaled_decimal(static_cast<std::int64_t>(stamp), exponent);
  char text[48];
  std::snprintf(text, sizeof text, "%llue-%d", static_cast<unsigned long long>(stamp), exponent);
  return std::strtod(text, nullptr);
}

/// Days from 1970-01-01 to a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t y, unsigned m, unsigned d) {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

/// The file header's start time (SYSTEMTIME: year, month, day of week, day, hour, minute,
/// second, milliseconds; UTC) in seconds since 1970; 0 for a date Python's datetime refuses,
/// as python-can does.
double start_seconds(const std::uint8_t* st) {
  const unsigned year = le16(st), month = le16(st + 2), day = le16(st + 6);
  const unsigned hour = le16(st + 8), minute = le16(st + 10), second = le16(st + 12);
  const unsigned ms = le16(st + 14);
  static constexpr unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (year < 1 || year > 9999 || month < 1 || month > 12 || hour > 23 || minute > 59 ||
      second > 59 || ms > 999) {
    return 0.0;
  }
  const bool leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
  const unsigned days_in_month = kDays[month - 1] + (month == 2 && leap ? 1 : 0);
  if (day < 1 || day > days_in_month) return 0.0;
  const std::int64_t seconds =
      days_from_civil(year, month, day) * 86400 + hour * 3600 + minute * 60 + second;
  // datetime.timestamp(): (microseconds) / 10**6, an integer division correctly rounded
  return scaled_decimal(seconds * 1000000 + static_cast<std::int64_t>(ms) * 1000, 6);
}

/// A frame's fields as python-can's Message holds them.
struct Message {
  std::uint32_t id = 0;
  bool extended = false, remote = false, fd = false, brs = false, esi = false, error = false;
  unsigned dlc = 0;  ///< Message.dlc (a length for the FD objects)
  unsigned len = 0;  ///< len(Message.data): up to 255 for CAN_FD_MESSAGE_64
  std::uint8_t data[can::kFdMaxLen] = {};
  std::uint16_t channel = 0;
};

void take_data(Message* m, const std::uint8_t* from, unsigned available) {
  std::memcpy(m->data, from, std::min<unsigned>(available, can::kFdMaxLen));
}

/// The fields of a frame object (its size checked: at least header + frame_fields_size).
Message read_message(const std::uint8_t* o, const ObjectHeader& h) {
  const std::uint8_t* p = o + full_header_size(h.version);
  Message m;
  std::uint32_t id = 0;
  switch (h.type) {
    case kCanMessage:
    case kCanMessage2:
      m.channel = le16(p);
      m.remote = (p[2] & 0x80) != 0;
      m.dlc = p[3];
      id = le32(p + 4);
      m.len = std::min(m.dlc, 8u);
      take_data(&m, p + 8, m.len);
      break;
    case kCanErrorExt:
      m.channel = le16(p);
      m.error = true;
      m.dlc = p[10];
      id = le32(p + 16);
      m.len = std::min(m.dlc, 8u);
      take_data(&m, p + 24, m.len);
      break;
    case kCanFdMessage: {
      static constexpr unsigned kFdDlc[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
      m.channel = le16(p);
      m.remote = (p[2] & 0x80) != 0;
      m.dlc = p[3] <= 15 ? kFdDlc[p[3]] : 64;
      id = le32(p + 4);
      m.fd = (p[13] & 0x1) != 0;
      m.brs = (p[13] & 0x2) != 0;
      m.esi = (p[13] & 0x4) != 0;
      m.len = std::min<unsigned>(p[14], can::kFdMaxLen);
      take_data(&m, p + 20, m.len);
      break;
    }
    case kCanFdMessage64: {
      static constexpr unsigned kFdDlc[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
      m.channel = p[0];
      m.dlc = p[1] <= 15 ? kFdDlc[p[1]] : 64;
      const unsigned valid = p[2];
      id = le32(p + 4);
      const std::uint32_t flags = le32(p + 12);
      m.remote = (flags & 0x0010) != 0;
      m.fd = (flags & 0x1000) != 0;
      m.brs = (flags & 0x2000) != 0;
      m.esi = (flags & 0x4000) != 0;
      // The data ends at the extension (ext data offset) or the object's end, as python-can
      // takes it; what is missing of `valid` bytes is zeros (CANoe's and binlog.dll's way).
      const std::uint8_t ext_offset = p[35];
      const std::int64_t field = std::min<std::int64_t>(
          valid,
          static_cast<std::int64_t>(ext_offset != 0 ? ext_offset : h.size) - h.header_size - 40);
      const std::int64_t in_object =
          static_cast<std::int64_t>(h.size) - static_cast<std::int64_t>(p + 40 - o);
      const std::int64_t present = std::max<std::int64_t>(0, std::min(field, in_object));
      m.len = valid;
      take_data(&m, p + 40, static_cast<unsigned>(present));
      break;
    }
    default:
      break;
  }
  m.extended = (id & kExtendedIdBit) != 0;
  m.id = id & can::kEffMask;
  return m;
}

/// The frame vmass-log-convert made of python-can's message (its checks and flags), or false
/// and *why.
bool to_frame(const Message& m, double time_s, can::CanFrame* f, std::string* why) {
  char text[96];
  if (!(std::fabs(time_s) < kMaxAbsTimeS)) {
    std::snprintf(text, sizeof text, "time %.6g s from 1970 is no log's", time_s);
    *why = text;
    return false;
  }
  *f = can::CanFrame{};
  // round(): to the nearest microsecond, halves to even, as Python's round()
  f->time_us = static_cast<std::int64_t>(std::nearbyint(time_s * 1e6));
  f->id = m.id;
  if (m.error) {
    f->flags = can::kError;
    f->len = static_cast<std::uint8_t>(m.len);
    std::memcpy(f->data, m.data, m.len);
    return true;
  }
  if (m.id > (m.extended ? can::kEffMask : can::kSffMask)) {
    std::snprintf(text, sizeof text, "id %X too large for an 11-bit id", m.id);
    *why = text;
    return false;
  }
  if (m.fd && !can::is_valid_fd_length(static_cast<int>(m.len))) {
    *why = "CAN FD length " + std::to_string(m.len) +
           " is not one of 0..8, 12, 16, 20, 24, 32, 48, 64";
    return false;
  }
  if (!m.fd && m.len > static_cast<unsigned>(can::kClassicMaxLen)) {
    *why = "classic frame of " + std::to_string(m.len) + " bytes";
    return false;
  }
  if (m.extended) f->flags = can::kExtended;
  if (m.remote) {  // a remote request: its DLC, no data (CAN FD has no remote frames)
    f->flags = static_cast<std::uint8_t>(f->flags | can::kRemote);
    f->len = static_cast<std::uint8_t>(std::min(m.dlc, 8u));
    return true;
  }
  if (m.fd) {
    f->flags = static_cast<std::uint8_t>(f->flags | can::kFd | (m.brs ? can::kFdBrs : 0) |
                                         (m.esi ? can::kFdEsi : 0));
  }
  f->len = static_cast<std::uint8_t>(m.len);
  std::memcpy(f->data, m.data, m.len);
  return true;
}

using io::read_failure;

}  // namespace

std::string blf_interface_name(std::uint16_t channel) {
  return "can" + std::to_string(channel == 0 ? 0 : channel - 1);
}

std::string BlfReader::object_type_name(std::uint32_t type) {
  switch (type) {
    case kCanMessage:
      return "CAN_MESSAGE";
    case 2:
      return "CAN_ERROR";
    case kLogContainer:
      return "LOG_CONTAINER";
    case 65:
      return "APP_TEXT";
    case kCanErrorExt:
      return "CAN_ERROR_EXT";
    case kCanMessage2:
      return "CAN_MESSAGE2";
    case 96:
      return "GLOBAL_MARKER";
    case kCanFdMessage:
      return "CAN_FD_MESSAGE";
    case kCanFdMessage64:
      return "CAN_FD_MESSAGE_64";
    case 104:
      return "CAN_FD_ERROR_64";
    default:
      return "object type " + std::to_string(type);
  }
}

class BlfReader::Impl {
 public:
  Impl(std::istream& in, const Limits& limits);
  ~Impl() { inflateEnd(&zs_); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Next next(Record* record, std::string* why);
  const std::string& read_error() const { return read_error_; }
  std::uint64_t without_frame(std::uint32_t type) const {
    return skipped_types_[std::min<std::uint32_t>(type, 256)];
  }
  std::size_t buffer_bytes() const { return file_.size() + data_.size(); }

 private:
  /// What a step of the reader came to: a record, or nothing yet (kMore: go on).
  enum class Step : std::uint8_t { kFrame, kNoFrame, kCorrupt, kMore };
  enum class State : std::uint8_t { kFileHeader, kObjects, kEnd };

  // ---- the file, buffered
  std::size_t file_avail() const { return file_end_ - file_begin_; }
  const std::uint8_t* file_data() const { return file_.data() + file_begin_; }
  void file_consume(std::size_t n) {
    file_begin_ += n;
    file_offset_ += n;
  }
  std::size_t file_fill(std::size_t n);
  std::uint64_t file_skip(std::uint64_t n);
  std::uint64_t file_end_offset() const { return file_offset_ + file_avail(); }

  // ---- the containers' data, buffered
  /// The bytes released for reading (a zlib container's are once its stream checked out).
  std::size_t data_avail() const { return data_ready_ - data_begin_; }
  const std::uint8_t* data_data() const { return data_.data() + data_begin_; }
  void data_consume(std::size_t n) {
    data_begin_ += n;
    data_offset_ += n;
  }
  std::uint64_t data_end_offset() const { return data_offset_ + data_avail(); }

  // ---- steps
  void read_file_header();
  Step parse_data(Record* record, std::string* why);
  bool search_data();
  void apply_cut();
  Step next_object(Record* record, std::string* why);
  Step search_file(std::string* why);
  Step open_container(const ObjectHeader& h, std::string* why);
  /// An object at the top level that is no container, its header at file_data().
  Step top_level_object(const ObjectHeader& h, Record* record, std::string* why);
  void inflate_some();
  /// Room for a chunk after data_end_ (the buffer compacted, or grown up to the limit).
  bool make_room();
  /// The container's data so far is dropped, its bytes skipped; `why` said at the cut.
  void drop_container(std::string why);
  /// The container's data ended (its zlib stream, or its stored bytes) and is released.
  void end_container();
  /// The containers' data does not go on after what it holds now; `why`, when given, is said
  /// once the objects before the cut are read.
  void cut_data(std::string why = {});
  /// The containers' data stops inside an object (not at its end, nor in padding).
  bool data_mid_object() const;
  void finish();

  /// An object's size that no object of its type has, "" when it is plausible.
  std::string size_problem(const ObjectHeader& h) const;
  /// A signature found by a search starts an object worth reading (a stricter check than an
  /// object where one is expected gets: a match in a frame's data bytes should not).
  bool plausible(const std::uint8_t* o, bool top_level) const;
  /// A frame object wholly at o; *why without the place for kCorrupt.
  Step decode(const std::uint8_t* o, const ObjectHeader& h, Record* record, std::string* why) const;
  std::string where_data(std::uint64_t offset);
  static std::string where_file(std::uint64_t offset) {
    return "at file offset " + std::to_string(offset);
  }
  void report(std::string why) { reports_.push_back(std::move(why)); }

  std::streambuf* in_;
  Limits limits_;
  State state_ = State::kFileHeader;
  std::deque<std::string> reports_;  ///< damage found, to give as records (a few at a time)
  /// Damage to say once the containers' data is read up to the offset (the frames before it
  /// come first).
  std::deque<std::pair<std::uint64_t, std::string>> notes_;
  std::array<std::uint64_t, 257> skipped_types_{};

  std::vector<std::uint8_t> file_;
  std::size_t file_begin_ = 0, file_end_ = 0;
  std::uint64_t file_offset_ = 0;  ///< of file_[file_begin_]
  bool file_eof_ = false;
  std::int64_t file_size_ = -1;  ///< when the stream can tell
  std::string read_error_;
  std::uint64_t header_file_size_ = 0;
  std::uint32_t header_size_ = 0;
  double start_s_ = 0.0;
  bool file_search_ = false, file_search_quiet_ = false;
  bool seen_container_ = false;  ///< a file of containers: only containers at its top level
  std::uint64_t file_search_from_ = 0;

  std::vector<std::uint8_t> data_;
  std::size_t data_begin_ = 0;
  std::size_t data_ready_ = 0;     ///< the end of the released bytes
  std::size_t data_end_ = 0;       ///< the end of the bytes inflated
  std::uint64_t data_offset_ = 0;  ///< of data_[data_begin_], in the containers' data
  std::uint64_t skip_ = 0;         ///< bytes of a skipped object still to come
  std::uint64_t cut_ = kNoCut;     ///< data offset after which the data does not go on
  bool data_search_ = false, data_search_quiet_ = false;
  std::uint64_t data_search_from_ = 0;
  std::string data_search_where_;
  struct Mark {
    std::uint64_t data_offset;  ///< where the container's data begins
    std::uint64_t file_offset;  ///< where the container is
  };
  std::deque<Mark> marks_;  ///< the containers whose data is in data_

  struct Container {
    bool active = false;
    std::uint64_t at = 0;         ///< file offset
    std::uint32_t size = 0;       ///< object size
    std::uint64_t remaining = 0;  ///< compressed bytes not read yet
    std::uint16_t method = 0;
    std::uint32_t declared = 0;  ///< uncompressed size in its header
    std::uint64_t inflated = 0;
  } container_;
  z_stream zs_{};
  std::string truncation_;  ///< the file ended inside something: said after its data
};

BlfReader::Impl::Impl(std::istream& in, const Limits& limits)
    : in_(in.rdbuf()), limits_(limits), file_(kFileBufferBytes), data_(kDataBufferBytes) {
  // A frame object must fit in the data buffer beside the data inflated after it.
  limits_.max_frame_object_bytes =
      std::min<std::uint32_t>(limits_.max_frame_object_bytes, kDataBufferBytes / 4);
  if (inflateInit(&zs_) != Z_OK) throw std::bad_alloc();
  if (in_ != nullptr) {
    const std::streamoff here = in_->pubseekoff(0, std::ios::cur, std::ios::in);
    const std::streamoff end = in_->pubseekoff(0, std::ios::end, std::ios::in);
    if (here >= 0 && end >= here && in_->pubseekpos(here, std::ios::in) == here) {
      file_size_ = end - here;
    }
  }
}

std::size_t BlfReader::Impl::file_fill(std::size_t n) {
  n = std::min(n, file_.size());
  if (file_avail() >= n) return file_avail();
  if (file_begin_ > 0) {
    std::memmove(file_.data(), file_data(), file_avail());
    file_end_ -= file_begin_;
    file_begin_ = 0;
  }
  while (file_end_ < n && !file_eof_) {
    std::streamsize got = 0;
    try {
      errno = 0;
      got = in_ == nullptr ? 0
                           : in_->sgetn(reinterpret_cast<char*>(file_.data() + file_end_),
                                        static_cast<std::streamsize>(file_.size() - file_end_));
      if (got <= 0 && errno != 0 && errno != EAGAIN) read_error_ = std::strerror(errno);
    } catch (const std::ios_base::failure& e) {
      read_error_ = read_failure(e);
      got = 0;
    }
    if (got <= 0) {
      file_eof_ = true;
      break;
    }
    file_end_ += static_cast<std::size_t>(got);
  }
  return file_avail();
}

std::uint64_t BlfReader::Impl::file_skip(std::uint64_t n) {
  std::uint64_t skipped = 0;
  while (skipped < n) {
    if (file_avail() == 0 && file_fill(file_.size()) == 0) break;
    const auto take = static_cast<std::size_t>(std::min<std::uint64_t>(file_avail(), n - skipped));
    file_consume(take);
    skipped += take;
  }
  return skipped;
}

std::string BlfReader::Impl::where_data(std::uint64_t offset) {
  while (marks_.size() >= 2 && marks_[1].data_offset <= data_offset_) marks_.pop_front();
  const Mark* mark = nullptr;
  for (const Mark& m : marks_) {
    if (m.data_offset > offset) break;
    mark = &m;
  }
  if (mark == nullptr) return "at byte " + std::to_string(offset) + " of the containers' data";
  return "at byte " + std::to_string(offset - mark->data_offset) +
         " of the data of the container at file offset " + std::to_string(mark->file_offset);
}

std::string BlfReader::Impl::size_problem(const ObjectHeader& h) const {
  if (h.size < kBaseHeader) {
    return object_type_name(h.type) + " of " + bytes_text(h.size) +
           ", less than the 16 of an object header";
  }
  if (is_frame_type(h.type)) {
    const std::size_t header = full_header_size(h.version);
    if (h.size > limits_.max_frame_object_bytes) {
      return object_type_name(h.type) + " claiming " + bytes_text(h.size) +
             " (no frame object takes more than " + std::to_string(limits_.max_frame_object_bytes) +
             ")";
    }
    if (header != 0 && h.size < header + frame_fields_size(h.type)) {
      return object_type_name(h.type) + " of " + bytes_text(h.size) + ", less than the " +
             std::to_string(header + frame_fields_size(h.type)) + " its fields take";
    }
    return {};
  }
  if (h.size > limits_.max_object_bytes) {
    return object_type_name(h.type) + " claiming " + bytes_text(h.size) +
           " (no object takes more than " + std::to_string(limits_.max_object_bytes >> 20) +
           " MiB)";
  }
  return {};
}

bool BlfReader::Impl::plausible(const std::uint8_t* o, bool top_level) const {
  const ObjectHeader h = parse_header(o);
  if (h.version != 1 && h.version != 2) return false;
  if (h.type == kLogContainer) {
    return top_level && (h.header_size == 16 || h.header_size == 32) &&
           h.size >= kContainerHeader && h.size <= limits_.max_container_bytes;
  }
  // In a file of containers the objects at the top level are containers (a stored container's
  // objects are no top-level objects).
  if (top_level && seen_container_) return false;
  return h.header_size == full_header_size(h.version) && h.size >= h.header_size &&
         size_problem(h).empty();
}

BlfReader::Impl::Step BlfReader::Impl::decode(const std::uint8_t* o, const ObjectHeader& h,
                                              Record* record, std::string* why) const {
  if (full_header_size(h.version) == 0) {
    *why = object_type_name(h.type) + " with object header version " + std::to_string(h.version) +
           " (neither 1 nor 2)";
    return Step::kCorrupt;
  }
  const Message m = read_message(o, h);
  const double time_s = offset_seconds(le64(o + 24), le32(o + 16)) + start_s_;
  if (!to_frame(m, time_s, &record->frame, why)) {
    *why = object_type_name(h.type) + ": " + *why;
    return Step::kCorrupt;
  }
  record->channel = m.channel;
  return Step::kFrame;
}

void BlfReader::Impl::read_file_header() {
  state_ = State::kObjects;
  const std::size_t got = file_fill(kFileHeaderFields);
  if (got < kFileHeaderFields) {
    if (read_error_.empty()) {
      report("truncated: the file ends at byte " + std::to_string(got) + ", inside its header (" +
             std::to_string(kFileHeaderFields) + " bytes at least)");
    }
    state_ = State::kEnd;
    return;
  }
  const std::uint8_t* h = file_data();
  header_size_ = le32(h + 4);
  header_file_size_ = le64(h + 16);
  start_s_ = start_seconds(h + 40);
  if (std::memcmp(h, "LOGG", 4) != 0 || header_size_ < kFileHeaderFields ||
      header_size_ > limits_.max_file_header_bytes) {
    report(std::memcmp(h, "LOGG", 4) != 0
               ? std::string("no BLF file header (LOGG) at the start of the file")
               : "a file header of " + bytes_text(header_size_) + " (writers write 144; " +
                     std::to_string(kFileHeaderFields) + " to " +
                     std::to_string(limits_.max_file_header_bytes) +
                     " are read): the objects are searched for after its first " +
                     std::to_string(kFileHeaderFields));
    header_size_ = kFileHeaderFields;
    header_file_size_ = 0;  // not to be trusted
    file_consume(kFileHeaderFields);
    file_search_ = true;
    file_search_quiet_ = true;
    return;
  }
  if (file_skip(header_size_) < header_size_) {
    if (read_error_.empty()) {
      report("truncated: the file ends at byte " + std::to_string(file_offset_) +
             ", inside its header of " + bytes_text(header_size_));
    }
    state_ = State::kEnd;
  }
}

BlfReader::Next BlfReader::Impl::next(Record* record, std::string* why) {
  for (;;) {
    if (!reports_.empty()) {
      *why = std::move(reports_.front());
      reports_.pop_front();
      return Next::kCorrupt;
    }
    if (state_ == State::kEnd) return Next::kEnd;
    if (state_ == State::kFileHeader) {
      read_file_header();
      continue;
    }
    Step step = parse_data(record, why);
    if (step == Step::kMore) {
      if (!reports_.empty()) continue;
      if (container_.active) {
        inflate_some();
        continue;
      }
      step = next_object(record, why);
    }
    switch (step) {
      case Step::kFrame:
        return Next::kFrame;
      case Step::kNoFrame:
        return Next::kNoFrame;
      case Step::kCorrupt:
        return Next::kCorrupt;
      case Step::kMore:
        break;
    }
  }
}

// ---- the containers' data

void BlfReader::Impl::cut_data(std::string why) {
  cut_ = data_end_offset();
  if (!why.empty()) notes_.emplace_back(cut_, std::move(why));
}

bool BlfReader::Impl::data_mid_object() const {
  if (skip_ > 0) return true;
  if (data_search_ || data_avail() > kPaddingWindow) return !data_search_ && data_avail() > 0;
  for (std::size_t i = 0; i < data_avail(); ++i) {
    if (data_data()[i] != 0) return true;
  }
  return false;
}

void BlfReader::Impl::apply_cut() {
  // Whatever reaches over the cut lost its continuation: quietly on from the next signature.
  if (data_search_ && !data_search_quiet_) {
    notes_.emplace_front(data_search_from_, "no object where one should start " +
                                                data_search_where_ + ": " +
                                                bytes_text(cut_ - data_search_from_) +
                                                " skipped up to damage in the data");
  }
  data_consume(data_avail());
  skip_ = 0;
  cut_ = kNoCut;
  data_search_ = true;
  data_search_quiet_ = true;
}

bool BlfReader::Impl::search_data() {
  while (data_avail() >= 4) {
    const std::size_t at = find_signature(data_data(), data_avail());
    if (at == data_avail()) {
      data_consume(data_avail() - 3);  // "LOB" may go on in the next bytes
      return false;
    }
    data_consume(at);
    if (data_avail() < kBaseHeader) return false;
    if (plausible(data_data(), false)) return true;
    data_consume(1);
  }
  return false;
}

BlfReader::Impl::Step BlfReader::Impl::parse_data(Record* record, std::string* why) {
  for (;;) {
    if (!notes_.empty() && notes_.front().first <= data_offset_) {
      *why = std::move(notes_.front().second);
      notes_.pop_front();
      return Step::kCorrupt;
    }
    // Nothing more can be read before more data comes: a cut there ends what is left.
    const auto wait = [this]() {
      if (cut_ == kNoCut || cut_ != data_end_offset()) return true;
      apply_cut();
      return false;
    };
    if (skip_ > 0) {
      const auto take = static_cast<std::size_t>(std::min<std::uint64_t>(skip_, data_avail()));
      data_consume(take);
      skip_ -= take;
      if (skip_ > 0) {
        if (wait()) return Step::kMore;
        continue;
      }
    }
    if (data_search_) {
      if (!search_data()) {
        if (wait()) return Step::kMore;
        continue;
      }
      data_search_ = false;
      if (!data_search_quiet_) {
        *why = "no object where one should start " + data_search_where_ + ": " +
               bytes_text(data_offset_ - data_search_from_) + " skipped to the next object (" +
               where_data(data_offset_) + ")";
        return Step::kCorrupt;
      }
    }
    // The next object: its signature after up to 4 bytes of padding (python-can's window).
    const std::size_t window = std::min<std::size_t>(data_avail(), kPaddingWindow + 4);
    const std::size_t at = find_signature(data_data(), window);
    if (at == window) {
      if (data_avail() < kPaddingWindow + 4) {
        if (wait()) return Step::kMore;
        continue;
      }
      data_search_ = true;
      data_search_quiet_ = false;
      data_search_from_ = data_offset_;
      data_search_where_ = where_data(data_offset_);
      continue;
    }
    if (data_avail() < at + kBaseHeader) {
      if (wait()) return Step::kMore;
      continue;
    }
    data_consume(at);
    const ObjectHeader h = parse_header(data_data());
    if (std::string problem = size_problem(h); !problem.empty()) {
      *why = problem + " (" + where_data(data_offset_) + ")";
      data_consume(4);  // its size cannot be trusted: on from the next signature
      data_search_ = true;
      data_search_quiet_ = true;
      return Step::kCorrupt;
    }
    if (!is_frame_type(h.type)) {
      ++skipped_types_[std::min<std::uint32_t>(h.type, 256)];
      skip_ = h.size;
      return Step::kNoFrame;
    }
    if (data_avail() < h.size) {
      if (wait()) return Step::kMore;
      continue;
    }
    const Step step = decode(data_data(), h, record, why);
    if (step == Step::kCorrupt) *why += " (" + where_data(data_offset_) + ")";
    data_consume(h.size);
    return step;
  }
}

bool BlfReader::Impl::make_room() {
  if (data_.size() - data_end_ >= kInflateChunk) return true;
  if (data_begin_ > 0) {
    std::memmove(data_.data(), data_data(), data_end_ - data_begin_);
    data_ready_ -= data_begin_;
    data_end_ -= data_begin_;
    data_begin_ = 0;
  }
  if (data_.size() - data_end_ >= kInflateChunk) return true;
  // A container's data is held until its zlib stream checks out: up to the limit.
  const std::size_t most = static_cast<std::size_t>(limits_.max_inflated_bytes) +
                           limits_.max_frame_object_bytes + kInflateChunk;
  if (data_.size() >= most) return data_end_ < data_.size();
  data_.resize(std::min(most, data_.size() * 2));
  return true;
}

void BlfReader::Impl::drop_container(std::string why) {
  Container& c = container_;
  data_end_ = data_ready_;  // what it inflated to is not to be trusted
  file_skip(c.remaining);
  c.active = false;
  cut_data(std::move(why));
}

void BlfReader::Impl::inflate_some() {
  Container& c = container_;
  const std::uint64_t compressed = c.size - kContainerHeader;
  if (c.inflated >= limits_.max_inflated_bytes || !make_room()) {
    drop_container("the container " + where_file(c.at) + " inflates to more than " +
                   bytes_text(limits_.max_inflated_bytes) + ": its objects are skipped");
    return;
  }
  const auto room = static_cast<std::size_t>(std::min<std::uint64_t>(
      {data_.size() - data_end_, kInflateChunk, limits_.max_inflated_bytes - c.inflated}));
  std::size_t in = 0;
  if (c.remaining > 0) {
    in = static_cast<std::size_t>(std::min<std::uint64_t>(file_fill(1), c.remaining));
  }
  const bool file_ended = c.remaining > 0 && in == 0;
  std::size_t used = 0;
  std::size_t made = 0;
  int rc = Z_OK;
  if (c.method == 0) {
    made = std::min(in, room);
    std::memcpy(data_.data() + data_end_, file_data(), made);
    used = made;
  } else {
    zs_.next_in = const_cast<Bytef*>(file_data());  // zlib's API: the input is only read
    zs_.avail_in = static_cast<uInt>(in);
    zs_.next_out = data_.data() + data_end_;
    zs_.avail_out = static_cast<uInt>(room);
    rc = inflate(&zs_, Z_NO_FLUSH);
    used = in - zs_.avail_in;
    made = room - zs_.avail_out;
  }
  file_consume(used);
  c.remaining -= used;
  data_end_ += made;
  c.inflated += made;
  if (c.method == 0) data_ready_ = data_end_;  // stored: nothing to check
  if (rc == Z_STREAM_END) {
    data_ready_ = data_end_;
    end_container();
    return;
  }
  if (rc != Z_OK && rc != Z_BUF_ERROR) {
    const char* msg = zs_.msg != nullptr ? zs_.msg : zError(rc);
    drop_container("the container " + where_file(c.at) + ": zlib: " + msg + " after " +
                   std::to_string(compressed - c.remaining) + " of its " +
                   std::to_string(compressed) + " compressed bytes: its objects are skipped");
    return;
  }
  if (used > 0 || made > 0) {
    if (c.method == 0 && c.remaining == 0) end_container();
    return;
  }
  // No progress: the file or the container's bytes ended before its zlib stream did.
  if (file_ended) {
    // A cut file: what the bytes there inflate to is read (as python-can reads it).
    data_ready_ = data_end_;
    if (truncation_.empty()) {
      truncation_ = "truncated: the file ends at byte " + std::to_string(file_offset_) +
                    ", inside the container " + where_file(c.at) + " of " + bytes_text(c.size) +
                    " (" + std::to_string(compressed - c.remaining) + " of its " +
                    std::to_string(compressed) + " compressed bytes there): the frames in the " +
                    bytes_text(c.inflated) + " they inflate to are read, the rest is lost";
    }
    c.active = false;
    cut_data();
    return;
  }
  if (c.method == 0) {
    end_container();
    return;
  }
  // The container ends, its zlib stream does not: damage (its size, or its data) that zlib's
  // check cannot tell, so nothing it inflated to is trusted.
  drop_container("the container " + where_file(c.at) + " ends before its zlib stream does (" +
                 bytes_text(c.inflated) + " inflated, not checked): its objects are skipped");
}

void BlfReader::Impl::end_container() {
  Container& c = container_;
  c.active = false;
  if (c.remaining > 0 && c.remaining <= 3 && file_fill(3) >= c.remaining) {
    bool zeros = true;  // padding counted in the object's size: not damage
    for (std::size_t i = 0; i < c.remaining; ++i) zeros = zeros && file_data()[i] == 0;
    if (zeros) {
      file_consume(static_cast<std::size_t>(c.remaining));
      c.remaining = 0;
    }
  }
  if (c.remaining > 0) {
    // The zlib stream (checked) ended inside the container: its size is wrong. The next
    // object is searched for from the stream's end on.
    file_search_ = true;
    file_search_quiet_ = true;
    notes_.emplace_back(data_end_offset(), "the container " + where_file(c.at) + " claims " +
                                               bytes_text(c.size) + ", its zlib data ends after " +
                                               std::to_string(c.size - c.remaining) +
                                               ": the next object is searched for from there");
    return;
  }
  if (c.inflated != c.declared) {
    notes_.emplace_back(data_end_offset(), "the container " + where_file(c.at) + " inflates to " +
                                               bytes_text(c.inflated) + ", its header says " +
                                               std::to_string(c.declared));
  }
}

// ---- the file's objects

BlfReader::Impl::Step BlfReader::Impl::search_file(std::string* why) {
  for (;;) {
    const std::size_t got = file_fill(kContainerHeader);
    if (got < 4 || (got < kBaseHeader && file_eof_)) {
      const std::uint64_t skipped = file_end_offset() - file_search_from_;
      file_consume(got);
      file_search_ = false;
      if (!file_search_quiet_) {
        report("no object where one should start " + where_file(file_search_from_) + ": the " +
               bytes_text(skipped) + " to the end of the file hold none");
      }
      finish();
      return Step::kMore;
    }
    const std::size_t at = find_signature(file_data(), got);
    if (at == got) {
      file_consume(got - 3);
      continue;
    }
    file_consume(at);
    if (file_fill(kContainerHeader) < kBaseHeader) continue;
    if (plausible(file_data(), true)) {
      file_search_ = false;
      if (!file_search_quiet_) {
        *why = "no object where one should start " + where_file(file_search_from_) + ": " +
               bytes_text(file_offset_ - file_search_from_) + " skipped to the next object (" +
               where_file(file_offset_) + ")";
        return Step::kCorrupt;
      }
      return Step::kMore;
    }
    file_consume(1);
  }
}

BlfReader::Impl::Step BlfReader::Impl::next_object(Record* record, std::string* why) {
  if (file_search_) {
    const Step step = search_file(why);
    if (step != Step::kMore || state_ == State::kEnd || file_search_) return step;
  }
  // The signature after up to 3 bytes of padding (writers pad an object to 4 bytes).
  const std::size_t got = file_fill(kContainerHeader);
  if (got == 0) {
    finish();
    return Step::kMore;
  }
  const std::size_t window = std::min<std::size_t>(got, 7);
  const std::size_t at = find_signature(file_data(), window);
  if (at == window) {
    if (got < kBaseHeader && file_eof_) {
      bool zeros = got <= 3;
      for (std::size_t i = 0; i < got; ++i) zeros = zeros && file_data()[i] == 0;
      if (!zeros && truncation_.empty()) {
        truncation_ = "truncated: the file ends at byte " + std::to_string(file_end_offset()) +
                      ", " + bytes_text(got) + " after the last whole object (" +
                      where_file(file_offset_) + ")";
      }
      file_consume(got);
      finish();
      return Step::kMore;
    }
    file_search_ = true;
    file_search_quiet_ = false;
    file_search_from_ = file_offset_;
    cut_data();  // the containers' data does not go on past damage
    return Step::kMore;
  }
  file_consume(at);
  if (file_avail() < kBaseHeader) {
    truncation_ = "truncated: the file ends at byte " + std::to_string(file_end_offset()) +
                  ", inside the header of the object " + where_file(file_offset_);
    file_consume(file_avail());
    finish();
    return Step::kMore;
  }
  const ObjectHeader h = parse_header(file_data());
  if (h.type == kLogContainer) return open_container(h, why);
  return top_level_object(h, record, why);
}

BlfReader::Impl::Step BlfReader::Impl::top_level_object(const ObjectHeader& h, Record* record,
                                                        std::string* why) {
  // An object outside the containers (python-can skips these; a frame is a frame).
  const std::uint64_t at_offset = file_offset_;
  if (data_mid_object()) {
    // Between two parts of one object: a container was lost (its type damaged, say). What the
    // next container holds is no continuation of what the last one left.
    cut_data("the containers' data breaks off " + bytes_text(data_avail()) + " into an object " +
             where_data(data_offset_) + ": an object of type " + std::to_string(h.type) + " " +
             where_file(at_offset) + " stands where a container should go on");
    return Step::kMore;
  }
  if (const std::string problem = size_problem(h); !problem.empty()) {
    *why = problem + " (" + where_file(at_offset) + ")";
    file_consume(4);
    file_search_ = true;
    file_search_quiet_ = true;
    cut_data();
    return Step::kCorrupt;
  }
  // A container's 16-byte header with another type, or a frame where a file of containers
  // has only containers: a container whose type was damaged. Skipped (as python-can skips
  // every object outside the containers) and said; what follows it is no continuation.
  if ((h.header_size == 16 && h.version == 1) || (seen_container_ && is_frame_type(h.type))) {
    *why = "an object of type " + std::to_string(h.type) + " " + where_file(at_offset) +
           (h.header_size == 16 ? " with a container's header" : " outside the containers") +
           " (a container whose type is damaged?): its " + bytes_text(h.size) + " are skipped";
    if (file_skip(h.size) < h.size && truncation_.empty() && read_error_.empty()) {
      truncation_ = "truncated: the file ends at byte " + std::to_string(file_offset_) +
                    ", inside the object of " + bytes_text(h.size) + " " + where_file(at_offset);
    }
    cut_data();
    return Step::kCorrupt;
  }
  if (!is_frame_type(h.type)) {
    ++skipped_types_[std::min<std::uint32_t>(h.type, 256)];
    if (file_skip(h.size) < h.size && truncation_.empty() && read_error_.empty()) {
      truncation_ = "truncated: the file ends at byte " + std::to_string(file_offset_) +
                    ", inside the " + object_type_name(h.type) + " of " + bytes_text(h.size) + " " +
                    where_file(at_offset);
    }
    return Step::kNoFrame;
  }
  if (file_fill(h.size) < h.size) {
    truncation_ = "truncated: the file ends at byte " + std::to_string(file_end_offset()) +
                  ", inside the " + object_type_name(h.type) + " of " + bytes_text(h.size) + " " +
                  where_file(at_offset);
    file_consume(file_avail());
    finish();
    return Step::kMore;
  }
  const Step step = decode(file_data(), h, record, why);
  if (step == Step::kCorrupt) *why += " (" + where_file(at_offset) + ")";
  file_consume(h.size);
  return step;
}

BlfReader::Impl::Step BlfReader::Impl::open_container(const ObjectHeader& h, std::string* why) {
  const std::uint64_t at = file_offset_;
  if (h.size < kContainerHeader || h.size > limits_.max_container_bytes) {
    *why = "LOG_CONTAINER of " + bytes_text(h.size) + " " + where_file(at) +
           " (a container takes " + std::to_string(kContainerHeader) + " bytes to " +
           std::to_string(limits_.max_container_bytes >> 20) + " MiB)";
    file_consume(4);
    file_search_ = true;
    file_search_quiet_ = true;
    cut_data();
    return Step::kCorrupt;
  }
  if (file_fill(kContainerHeader) < kContainerHeader) {
    truncation_ = "truncated: the file ends at byte " + std::to_string(file_end_offset()) +
                  ", inside the header of the container " + where_file(at);
    file_consume(file_avail());
    cut_data();
    finish();
    return Step::kMore;
  }
  Container& c = container_;
  c.at = at;
  c.size = h.size;
  c.method = le16(file_data() + 16);
  c.declared = le32(file_data() + 24);
  c.remaining = h.size - kContainerHeader;
  c.inflated = 0;
  file_consume(kContainerHeader);
  if (c.method != 0 && c.method != 2) {
    *why = "the container " + where_file(at) + " has compression method " +
           std::to_string(c.method) + " (0: none, 2: zlib): its " + bytes_text(c.remaining) +
           " are skipped";
    file_skip(c.remaining);
    cut_data();
    return Step::kCorrupt;
  }
  seen_container_ = true;
  if (c.method == 2) inflateReset(&zs_);
  while (marks_.size() >= 2 && marks_[1].data_offset <= data_offset_) marks_.pop_front();
  if (!marks_.empty() && marks_.back().data_offset == data_end_offset()) marks_.pop_back();
  marks_.push_back({data_end_offset(), at});
  c.active = true;
  return Step::kMore;
}

void BlfReader::Impl::finish() {
  state_ = State::kEnd;
  if (!read_error_.empty()) return;  // the read error is the problem, not the file
  if (truncation_.empty() && file_size_ >= 0 && header_file_size_ > header_size_ &&
      header_file_size_ > static_cast<std::uint64_t>(file_size_)) {
    truncation_ = "truncated: the file has " + bytes_text(static_cast<std::uint64_t>(file_size_)) +
                  ", its header says " + std::to_string(header_file_size_) +
                  ": the end of the log is missing";
  }
  if (data_search_ && !data_search_quiet_) {
    notes_.emplace_back(data_end_offset(), "no object where one should start " +
                                               data_search_where_ + ": the " +
                                               bytes_text(data_end_offset() - data_search_from_) +
                                               " to the end of the data hold none");
    data_search_quiet_ = true;
  } else if (!data_search_ && truncation_.empty() && data_avail() + skip_ > kPaddingWindow) {
    notes_.emplace_back(data_end_offset(), "truncated: the containers' data ends " +
                                               bytes_text(data_avail()) + " into an object " +
                                               where_data(data_offset_));
  }
  cut_data();
  apply_cut();
  for (auto& note : notes_) report(std::move(note.second));
  notes_.clear();
  if (!truncation_.empty()) report(truncation_);
}

// ---- BlfReader

BlfReader::BlfReader(std::istream& in) : BlfReader(in, Limits{}) {}

BlfReader::BlfReader(std::istream& in, const Limits& limits)
    : impl_(std::make_unique<Impl>(in, limits)) {}

BlfReader::~BlfReader() = default;

BlfReader::Next BlfReader::next(Record* record, std::string* why) {
  const Next got = impl_->next(record, why);
  if (got != Next::kEnd) ++record_number_;
  return got;
}

const std::string& BlfReader::read_error() const { return impl_->read_error(); }

std::uint64_t BlfReader::objects_without_frame(std::uint32_t type) const {
  return impl_->without_frame(type);
}

std::size_t BlfReader::buffer_bytes() const { return impl_->buffer_bytes(); }

}  // namespace vmass::runtime
