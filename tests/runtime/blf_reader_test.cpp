// Vector BLF read natively (vmass/runtime/blf_reader.hpp), on files laid out byte by byte
// (blf_test_writer.hpp): every frame object python-can reads, with the frame vmass-log-convert
// made of it; header versions 1 and 2, 10 us and ns time stamps, objects that go on in the next
// container, stored and zlib containers, objects of other types skipped and counted. Damage
// costs nothing but what it destroys: a file cut at every byte gives the frames before the cut
// and says "truncated" and where; a byte flipped anywhere never crashes, never gives a frame
// from a zlib container whose data does not check out, and every report names a file offset;
// sizes that claim gigabytes allocate nothing (the reader's buffers stay bounded, and a child
// reads them under an address-space limit). (tests/logs/blf_native_test.sh checks the frames
// against python-can on files python-can writes, whole, cut and damaged.)
#include "vmass/runtime/blf_reader.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "blf_test_writer.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/runtime/blf_log_frame_source.hpp"
#include "vmass/runtime/log_frame_source.hpp"

namespace vmass::runtime {
namespace {

using namespace blftest;  // NOLINT(google-build-using-namespace): the test's own writer

constexpr std::int64_t kStartUs = 1622534400000000;  // 2021-06-01 08:00:00.000 UTC

/// What a reader gave: each frame as the candump -l line of it, each damage's message.
struct Read {
  std::vector<std::string> frames;
  std::vector<std::string> corrupt;
  std::int64_t records = 0;
  std::size_t max_buffer_bytes = 0;
};

Read read_blf(const std::string& file, const BlfReader::Limits& limits = {}) {
  std::istringstream in(file);
  BlfReader reader(in, limits);
  Read r;
  BlfReader::Record record;
  std::string why;
  for (;;) {
    const BlfReader::Next got = reader.next(&record, &why);
    r.max_buffer_bytes = std::max(r.max_buffer_bytes, reader.buffer_bytes());
    if (got == BlfReader::Next::kEnd) break;
    ++r.records;
    if (got == BlfReader::Next::kFrame) {
      std::string line = can::format_candump_line(record.frame, blf_interface_name(record.channel));
      line.pop_back();
      r.frames.push_back(line);
    } else if (got == BlfReader::Next::kCorrupt) {
      r.corrupt.push_back(why);
    }
  }
  EXPECT_EQ(reader.record_number(), r.records);
  return r;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + "\n";
  return s;
}

/// Every frame object python-can reads, each with the frame expected of it.
struct Case {
  std::string object;
  std::string line;  ///< candump -l of the frame, "" for an object without one
};

std::vector<Case> every_kind_of_object() {
  return {
      {object(1, can_message_fields(1, 0x123, {0xDE, 0xAD, 0xBE}), 1500000),
       "(1622534400.001500) can0 123#DEADBE"},
      {object(1, can_message_fields(2, 0x80000000u | 0x18FF1010, {1, 2, 3, 4, 5, 6, 7, 8}),
              2000000),
       "(1622534400.002000) can1 18FF1010#0102030405060708"},
      // a remote request keeps its DLC; no data
      {object(1, can_message_fields(1, 0x321, {}, 4, 0x80), 2500000),
       "(1622534400.002500) can0 321#R4"},
      // a DLC above 8 on a classic frame: 8 data bytes
      {object(1, can_message_fields(1, 0x124, {9, 8, 7, 6, 5, 4, 3, 2}, 12), 2600000),
       "(1622534400.002600) can0 124#0908070605040302"},
      {object(86, can_message_fields(3, 0x7FF, {0x11, 0x22}, -1, 0, true), 3000000),
       "(1622534400.003000) can2 7FF#1122"},
      // header version 2, time stamps in 10 us
      {object(1, can_message_fields(1, 0x100, {0xAB}), 12345, 1, 2),
       "(1622534400.123450) can0 100#AB"},
      // channel 0 (no writer writes it) is can0 too
      {object(1, can_message_fields(0, 0x101, {}), 4000000), "(1622534400.004000) can0 101#"},
      {object(73, error_ext_fields(1, 0x55, {1, 2}), 5000000),
       "(1622534400.005000) can0 20000055#0102"},
      // CAN FD, BRS: DLC 9 is 12 bytes
      {object(100, can_fd_fields(1, 0x200, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, 9, 0x3),
              6000000),
       "(1622534400.006000) can0 200##10102030405060708090A0B0C"},
      // a classic frame in a CAN FD object (no EDL)
      {object(100, can_fd_fields(2, 0x201, {1, 2, 3}, 3, 0), 7000000),
       "(1622534400.007000) can1 201#010203"},
      {object(101,
              can_fd64_fields(1, 0x80000000u | 0x1ABCDE,
                              {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}, 10,
                              0x1000 | 0x4000),
              8000000),
       "(1622534400.008000) can0 001ABCDE##20102030405060708090A0B0C0D0E0F10"},
      // the data field ends at the extension data: what is missing of the valid bytes is zeros
      {object(101,
              can_fd64_fields(2, 0x202, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, 9, 0x1000,
                              32 + 40 + 4, 12),
              9000000),
       "(1622534400.009000) can1 202##0010203040000000000000000"},
      {object(65, le(0, 4) + le(5, 4) + le(0, 4) + "hello", 9500000), ""},  // APP_TEXT
      {object(300, std::string(40, 'x'), 9600000), ""},                     // unknown type
  };
}

std::string inner_of(const std::vector<Case>& cases) {
  std::string inner;
  for (const Case& c : cases) inner += c.object;
  return inner;
}

std::vector<std::string> lines_of(const std::vector<Case>& cases) {
  std::vector<std::string> lines;
  for (const Case& c : cases) {
    if (!c.line.empty()) lines.push_back(c.line);
  }
  return lines;
}

TEST(BlfReaderTest, ReadsEveryFrameObjectAsPythonCanDoes) {
  const std::vector<Case> cases = every_kind_of_object();
  for (const bool compress : {true, false}) {
    SCOPED_TRACE(compress ? "zlib" : "stored");
    const Built b = build(inner_of(cases), 128 * 1024, compress);
    const Read r = read_blf(b.file);
    EXPECT_EQ(joined(r.frames), joined(lines_of(cases)));
    EXPECT_TRUE(r.corrupt.empty()) << joined(r.corrupt);
    EXPECT_EQ(r.records, static_cast<std::int64_t>(cases.size()));
  }
}

TEST(BlfReaderTest, ObjectsGoOnInTheNextContainer) {
  const std::vector<Case> cases = every_kind_of_object();
  for (const bool compress : {true, false}) {
    for (const std::size_t container_bytes : {1u, 7u, 50u, 333u}) {
      SCOPED_TRACE(std::to_string(container_bytes) + (compress ? " zlib" : " stored"));
      const Built b = build(inner_of(cases), container_bytes, compress);
      const Read r = read_blf(b.file);
      EXPECT_EQ(joined(r.frames), joined(lines_of(cases)));
      EXPECT_TRUE(r.corrupt.empty()) << joined(r.corrupt);
    }
  }
}

TEST(BlfReaderTest, ObjectsOfOtherTypesAreCountedAndSkipped) {
  const std::string inner = object(65, "text", 1) + object(1, can_message_fields(1, 1, {}), 2) +
                            object(65, "more text", 3) + object(999, "", 4) +
                            object(96, std::string(100, 'm'), 5);
  std::istringstream in(build(inner, 64 * 1024, true).file);
  BlfReader reader(in);
  BlfReader::Record record;
  std::string why;
  std::vector<BlfReader::Next> got;
  for (BlfReader::Next n; (n = reader.next(&record, &why)) != BlfReader::Next::kEnd;) {
    got.push_back(n);
  }
  using N = BlfReader::Next;
  EXPECT_EQ(got, (std::vector<N>{N::kNoFrame, N::kFrame, N::kNoFrame, N::kNoFrame, N::kNoFrame}));
  EXPECT_EQ(reader.objects_without_frame(65), 2u);
  EXPECT_EQ(reader.objects_without_frame(96), 1u);
  EXPECT_EQ(reader.objects_without_frame(999), 1u);  // counted with every type above 255
  EXPECT_EQ(reader.objects_without_frame(256), 1u);
  EXPECT_EQ(reader.objects_without_frame(1), 0u);
  EXPECT_EQ(BlfReader::object_type_name(65), "APP_TEXT");
  EXPECT_EQ(BlfReader::object_type_name(999), "object type 999");
}

TEST(BlfReaderTest, AFileWithoutContainersHasItsFramesAtTheTopLevel) {
  // python-can reads only containers; a file of objects without containers (as early writers
  // wrote it) has its frames read all the same. In a file of containers an object at the top
  // level is a damaged container: said and skipped, as python-can skips it.
  const std::string frames = object(1, can_message_fields(1, 0x10, {1}), 1000) +
                             object(65, "text", 1500) +
                             object(1, can_message_fields(2, 0x11, {2}), 2000);
  Read r = read_blf(build("", 1024, true, {}, frames).file);
  EXPECT_EQ(joined(r.frames), "(1622534400.000001) can0 010#01\n(1622534400.000002) can1 011#02\n");
  EXPECT_TRUE(r.corrupt.empty()) << joined(r.corrupt);

  const Built b = build(object(1, can_message_fields(1, 0x12, {3}), 3000), 1024, true, {},
                        object(1, can_message_fields(1, 0x13, {4}), 4000));
  r = read_blf(b.file);
  EXPECT_EQ(joined(r.frames), "(1622534400.000003) can0 012#03\n");
  EXPECT_EQ(joined(r.corrupt), "an object of type 1 at file offset " +
                                   std::to_string(b.containers[0].end) +
                                   " outside the containers (a container whose type is "
                                   "damaged?): its 48 bytes are skipped\n");
}

TEST(BlfReaderTest, TimeIsTheHeadersStartPlusTheOffset) {
  const std::string inner = object(1, can_message_fields(1, 1, {}), 1);       // 1 ns
  const std::string tens = object(1, can_message_fields(1, 1, {}), 1, 1);     // 10 us
  const std::string half = object(1, can_message_fields(1, 1, {}), 2500, 2);  // 2.5 us: even
  SystemTime leap_day{2024, 2, 4, 29, 23, 59, 59, 999};
  EXPECT_EQ(joined(read_blf(build(inner + tens + half, 4096, true, leap_day).file).frames),
            "(1709251199.999000) can0 001#\n(1709251199.999010) can0 001#\n"
            "(1709251199.999002) can0 001#\n");
  // A date Python's datetime refuses (30 February, a millisecond of 1000) is time 0, as in
  // python-can: the offsets alone.
  for (const SystemTime bad :
       {SystemTime{2023, 2, 4, 30, 0, 0, 0, 0}, SystemTime{2023, 1, 0, 1, 0, 0, 0, 1000}}) {
    EXPECT_EQ(joined(read_blf(build(tens, 4096, true, bad).file).frames),
              "(0000000000.000010) can0 001#\n");
  }
}

TEST(BlfReaderTest, FramesThatCannotBeCanFramesAreCorruptRecords) {
  const std::string inner =
      object(1, can_message_fields(1, 0x800, {1}), 1000) +  // 11 bit
      object(101, can_fd64_fields(1, 0x300, {1, 2, 3, 4, 5, 6, 7, 8, 9}, 9, 0x1000), 2000) +
      object(100, can_fd_fields(1, 0x301, std::vector<int>(12, 1), 9, 0), 3000) +  // no EDL
      object(1, can_message_fields(1, 0x302, {}), 1ull << 62, 1) +                 // year 10^6
      object(1, can_message_fields(1, 0x303, {3}), 4000);
  const Built b = build(inner, 4096, true);
  const Read r = read_blf(b.file);
  EXPECT_EQ(joined(r.frames), "(1622534400.000004) can0 303#03\n");
  ASSERT_EQ(r.corrupt.size(), 4u) << joined(r.corrupt);
  EXPECT_EQ(r.corrupt[0],
            "CAN_MESSAGE: id 800 too large for an 11-bit id (at byte 0 of the data of the "
            "container at file offset 144)");
  EXPECT_EQ(r.corrupt[1],
            "CAN_FD_MESSAGE_64: CAN FD length 9 is not one of 0..8, 12, 16, 20, 24, 32, 48, 64 "
            "(at byte 48 of the data of the container at file offset 144)");
  EXPECT_EQ(r.corrupt[2],
            "CAN_FD_MESSAGE: classic frame of 12 bytes (at byte 130 of the data of the "
            "container at file offset 144)");
  EXPECT_EQ(r.corrupt[3],
            "CAN_MESSAGE: time 4.61185e+13 s from 1970 is no log's (at byte 246 of the data of "
            "the container at file offset 144)");
}

/// A file of a few containers, objects going on in the next, objects of other types between:
/// its frames (as read whole) and where each frame's object ends in the containers' data.
struct Subject {
  Built built;
  std::vector<std::string> frames;
  std::vector<std::size_t> frame_ends;
  /// The frames whose objects end in the data of the containers wholly before file offset at.
  std::size_t frames_before(std::size_t at) const {
    std::size_t data = 0;
    for (std::size_t k = 0; k < built.containers.size() && built.containers[k].end <= at; ++k) {
      data = k + 1 < built.containers.size() ? built.containers[k + 1].data_begin : SIZE_MAX;
    }
    std::size_t n = 0;
    while (n < frame_ends.size() && frame_ends[n] <= data) ++n;
    return n;
  }
};

Subject damage_subject(bool compress) {
  Subject s;
  std::string inner;
  for (int i = 0; i < 40; ++i) {
    const std::uint64_t stamp = 1000000ull * static_cast<unsigned>(i);
    switch (i % 4) {
      case 0:
        inner += object(
            1,
            can_message_fields(static_cast<std::uint16_t>(1 + i % 3), 0x100 + i, {i, i + 1, i + 2}),
            stamp);
        break;
      case 1:
        inner += object(100, can_fd_fields(2, 0x200 + i, std::vector<int>(16, i), 10, 3), stamp);
        break;
      case 2:
        inner += object(101, can_fd64_fields(1, 0x300 + i, std::vector<int>(12, i), 9, 0x1000),
                        stamp, 2, 2);
        break;
      default:
        inner += object(65, std::string(static_cast<std::size_t>(i), 't'), stamp);
        break;
    }
    if (i % 4 != 3) s.frame_ends.push_back(inner.size());
  }
  s.built = build(inner, 700, compress);
  s.frames = read_blf(s.built.file).frames;
  return s;
}

bool names_a_place(const std::string& why) {
  return why.find("file offset") != std::string::npos ||
         why.find("the file ends at byte") != std::string::npos ||
         why.find("the file has") != std::string::npos ||
         why.find("file header") != std::string::npos;
}

std::vector<std::string> first(const std::vector<std::string>& v, std::size_t n) {
  return {v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(n, v.size()))};
}

TEST(BlfReaderTest, ACutFileGivesTheFramesBeforeTheCutAndSaysWhere) {
  for (const bool compress : {true, false}) {
    const Subject s = damage_subject(compress);
    ASSERT_EQ(s.frames.size(), 30u);
    ASSERT_EQ(s.built.containers.size(), 5u);
    std::size_t longest = 0;
    for (std::size_t cut = 1; cut < s.built.file.size(); ++cut) {
      SCOPED_TRACE("cut at " + std::to_string(cut) + (compress ? " zlib" : " stored"));
      const Read r = read_blf(s.built.file.substr(0, cut));
      // the frames before the cut, in order, at least those of the containers before it
      ASSERT_LE(r.frames.size(), s.frames.size());
      ASSERT_EQ(joined(r.frames), joined(first(s.frames, r.frames.size())));
      ASSERT_GE(r.frames.size(), s.frames_before(cut));
      ASSERT_GE(r.frames.size(), longest);  // a longer file never gives fewer frames
      longest = r.frames.size();
      // and one message, that says so and where
      ASSERT_EQ(r.corrupt.size(), 1u) << joined(r.corrupt);
      EXPECT_EQ(r.corrupt[0].rfind("truncated: ", 0), 0u) << r.corrupt[0];
      EXPECT_TRUE(names_a_place(r.corrupt[0])) << r.corrupt[0];
    }
    EXPECT_EQ(longest, s.frames.size());  // the last object is no frame: all of them
  }
}

TEST(BlfReaderTest, AByteFlippedAnywhereIsReportedOrHarmlessNeverGarbageFromZlib) {
  for (const bool compress : {true, false}) {
    const Subject s = damage_subject(compress);
    for (std::size_t at = 0; at < s.built.file.size(); ++at) {
      for (const int flip : {0xFF, 0x01, 0x80}) {
        SCOPED_TRACE("byte " + std::to_string(at) + " ^ " + std::to_string(flip) +
                     (compress ? " zlib" : " stored"));
        std::string damaged = s.built.file;
        damaged[at] = static_cast<char>(damaged[at] ^ flip);
        const Read r = read_blf(damaged);
        ASSERT_LE(r.records, static_cast<std::int64_t>(damaged.size()));
        for (const std::string& why : r.corrupt) ASSERT_TRUE(names_a_place(why)) << why;
        if (at >= 144) {  // past the file header: the containers before the damaged one read
          const std::size_t before = s.frames_before(at);
          ASSERT_EQ(joined(first(r.frames, before)), joined(first(s.frames, before)))
              << joined(r.corrupt);
        }
        if (compress && (at < 40 || at >= 56)) {
          // zlib checks its data: every frame read is one of the file's, in order (the start
          // time, bytes 40..55, moves them all)
          std::size_t k = 0;
          for (const std::string& line : r.frames) {
            while (k < s.frames.size() && s.frames[k] != line) ++k;
            ASSERT_LT(k, s.frames.size()) << "a frame that is not in the file: " << line;
            ++k;
          }
        }
      }
    }
  }
}

TEST(BlfReaderTest, RandomDamageIsBoundedAndLocated) {
  // Bytes overwritten, sizes written over, ranges deleted or doubled, several at once: no
  // crash (the sanitizer builds run this too), a bounded number of records, every report
  // located, and the frames of the containers before the first damage read as they were.
  std::mt19937 random(20261205);
  for (const bool compress : {true, false}) {
    const Subject s = damage_subject(compress);
    for (int round = 0; round < 1500; ++round) {
      std::string damaged = s.built.file;
      std::size_t first_damage = damaged.size();
      const int edits = 1 + static_cast<int>(random() % 4);
      for (int e = 0; e < edits && damaged.size() > 8; ++e) {
        const std::size_t at = random() % damaged.size();
        first_damage = std::min(first_damage, at);
        switch (random() % 4) {
          case 0:
            damaged[at] = static_cast<char>(random());
            break;
          case 1: {  // a size: small, huge, or off by a little
            const std::uint32_t sizes[] = {
                0,  1,  15,         16,         31,
                32, 48, 0x7FFFFFFF, 0xFFFFFFFF, static_cast<std::uint32_t>(random() % 2000)};
            damaged.replace(at, std::min<std::size_t>(4, damaged.size() - at),
                            le(sizes[random() % 10], 4).substr(0, damaged.size() - at));
            break;
          }
          case 2:
            damaged.erase(at, random() % 300);
            break;
          default:
            damaged.insert(at, damaged.substr(at, random() % 300));
            break;
        }
      }
      SCOPED_TRACE("round " + std::to_string(round) + (compress ? " zlib" : " stored"));
      const Read r = read_blf(damaged);
      ASSERT_LE(r.records, static_cast<std::int64_t>(damaged.size()));
      for (const std::string& why : r.corrupt) ASSERT_TRUE(names_a_place(why)) << why;
      if (first_damage >= 144) {
        const std::size_t before = s.frames_before(first_damage);
        ASSERT_EQ(joined(first(r.frames, before)), joined(first(s.frames, before)));
      }
    }
  }
}

TEST(BlfReaderTest, SizesInTheFileAreNeverAllocated) {
  const std::string frame = object(1, can_message_fields(1, 0x42, {1}), 1000);
  const std::string huge_inner = "LOBJ" + le(32, 2) + le(1, 2) + le(0xFFFFFFF0u, 4) + le(65, 4);
  const std::string huge_frame = "LOBJ" + le(32, 2) + le(1, 2) + le(0xFFFFFFF0u, 4) + le(1, 4);
  const std::string huge_container = "LOBJ" + le(16, 2) + le(1, 2) + le(0xFFFFFFF0u, 4) +
                                     le(10, 4) + le(2, 2) + std::string(6, '\0') +
                                     le(0xFFFFFFF0u, 4) + std::string(4, '\0');
  // 64 MiB of zeros compress to 64 KiB: more than a container may inflate to.
  const std::string bomb = container(std::string(64u << 20, '\0'), true);
  std::string big_header = build(frame, 1024, true).file;
  big_header.replace(4, 4, le(0xFFFFFFFFu, 4));
  const std::string after = std::to_string(build(frame, 4096, true).containers[0].end);
  const std::vector<std::pair<std::string, std::string>> files = {
      {build(frame + huge_inner + std::string(64, 'x') + frame, 4096, true).file,
       "APP_TEXT claiming 4294967280 bytes (no object takes more than 16 MiB) (at byte 48 of "
       "the data of the container at file offset 144)"},
      {build(frame + huge_frame + std::string(64, 'x') + frame, 4096, true).file,
       "CAN_MESSAGE claiming 4294967280 bytes (no frame object takes more than 4096) (at byte "
       "48 of the data of the container at file offset 144)"},
      {build(frame, 4096, true, {}, huge_container + container(frame, true)).file,
       "LOG_CONTAINER of 4294967280 bytes at file offset " + after +
           " (a container takes 32 bytes to 64 MiB)"},
      {build(frame, 4096, true, {}, bomb + container(frame, true)).file,
       "the container at file offset " + after +
           " inflates to more than 16777216 bytes: its objects are skipped"},
      {big_header,
       "a file header of 4294967295 bytes (writers write 144; 72 to 65536 are read): the "
       "objects are searched for after its first 72"},
  };
  for (const auto& [file, expected] : files) {
    SCOPED_TRACE(expected);
    const Read r = read_blf(file);
    ASSERT_FALSE(r.corrupt.empty());
    EXPECT_EQ(r.corrupt[0], expected);
    EXPECT_GE(r.frames.size(), 1u);
    EXPECT_LE(r.max_buffer_bytes, (17u << 20) + (256u << 10));
  }
  // Under a limit of its address space 64 MiB above what it uses: a reader that allocated
  // what the file claims would die of it. (Not under a sanitizer: its shadow memory.)
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the address-space limit is not for sanitizers";
#else
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
  GTEST_SKIP() << "the address-space limit is not for sanitizers";
#endif
#endif
  for (const auto& [file, expected] : files) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      long pages = 0;
      if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
        std::fclose(statm);
      }
      const rlim_t limit = static_cast<rlim_t>(pages) * sysconf(_SC_PAGESIZE) + (64u << 20);
      const rlimit rl{limit, limit};
      if (pages == 0 || setrlimit(RLIMIT_AS, &rl) != 0) _exit(3);
      std::istringstream in(file);
      BlfReader reader(in);
      BlfReader::Record record;
      std::string why;
      while (reader.next(&record, &why) != BlfReader::Next::kEnd) {
      }
      _exit(0);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << expected << ": " << status;
  }
#endif
}

TEST(BlfReaderTest, BadZlibDataCostsItsContainerAlone) {
  std::string inner;
  for (int i = 0; i < 3; ++i) inner += object(1, can_message_fields(1, 0x10 + i, {i}), 1000);
  const std::string bad = "LOBJ" + le(16, 2) + le(1, 2) + le(32 + 8, 4) + le(10, 4) + le(2, 2) +
                          std::string(6, '\0') + le(100, 4) + std::string(4, '\0') + "garbage!";
  const Built b = build(inner, 48, true, {},
                        bad + container(object(1, can_message_fields(1, 0x20, {}), 2000), true));
  const Read r = read_blf(b.file);
  EXPECT_EQ(joined(r.frames),
            "(1622534400.000001) can0 010#00\n(1622534400.000001) can0 011#01\n"
            "(1622534400.000001) can0 012#02\n(1622534400.000002) can0 020#\n");
  ASSERT_EQ(r.corrupt.size(), 1u);
  EXPECT_EQ(r.corrupt[0],
            "the container at file offset " + std::to_string(b.containers.back().end) +
                ": zlib: incorrect header check after 2 of its 8 compressed bytes: its objects "
                "are skipped");
}

class BlfLogFrameSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char name[] = "/tmp/vmass_blf_source_XXXXXX";
    ASSERT_NE(mkdtemp(name), nullptr);
    dir_ = name;
  }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }
  std::string write(const std::string& name, const std::string& content) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }
  std::string dir_;
};

TEST_F(BlfLogFrameSourceTest, EveryToolReadsBlfNativelyObjectByObject) {
  const std::string inner = object(1, can_message_fields(1, 0x10, {1}), 1000) +
                            object(65, "text", 1500) +
                            object(1, can_message_fields(1, 0x800, {1}), 1800) +
                            object(1, can_message_fields(2, 0x11, {2}), 2000);
  const std::string path = write("drive.bin", build(inner, 4096, true).file);
  std::string error;
  std::unique_ptr<LogFrameSource> source = open_log_frame_source(path, &error);
  ASSERT_NE(source, nullptr) << error;
  EXPECT_EQ(source->format(), can::LogFormat::kBlf);
  EXPECT_EQ(source->unit(), "record");
  EXPECT_NE(dynamic_cast<BlfLogFrameSource*>(source.get()), nullptr);
  std::vector<std::string> errors;
  source->on_error([&errors](const can::CandumpError& e) { errors.push_back(e.message); });
  can::CanFrame frame;
  std::vector<std::string> got;
  while (source->read(&frame, 0) == FrameSource::Read::kFrame) {
    got.push_back(std::string(source->interface_name()) + " " + std::to_string(frame.id) + " " +
                  std::to_string(source->position()));
  }
  EXPECT_EQ(got, (std::vector<std::string>{"can0 16 1", "can1 17 4"}));
  EXPECT_EQ(errors, (std::vector<std::string>{
                        path + ":record 3: CAN_MESSAGE: id 800 too large for an 11-bit id (at "
                               "byte 84 of the data of the container at file offset 144)"}));
  EXPECT_EQ(source->stats().lines, 4u);
  EXPECT_EQ(source->stats().frames, 2u);
  EXPECT_EQ(source->stats().comments, 1u);
  EXPECT_EQ(source->stats().corrupt, 1u);
  EXPECT_EQ(source->problem(), "");

  // --interface can1: channel 2 alone, the other counted
  std::unique_ptr<LogFrameSource> one = open_log_frame_source(path, &error);
  ASSERT_NE(one, nullptr);
  one->select_interface("can1");
  ASSERT_EQ(one->read(&frame, 0), FrameSource::Read::kFrame);
  EXPECT_EQ(frame.id, 0x11u);
  EXPECT_EQ(one->read(&frame, 0), FrameSource::Read::kEnd);
  EXPECT_EQ(one->interface_selection()->skipped(), 1u);
}

TEST_F(BlfLogFrameSourceTest, ACutHeaderIsNoFramesWithTheReason) {
  const std::string path = write("cut.blf", build("", 4096, true).file.substr(0, 60));
  std::string error;
  std::unique_ptr<LogFrameSource> source = open_log_frame_source(path, &error);
  ASSERT_NE(source, nullptr) << error;
  can::CanFrame frame;
  EXPECT_EQ(source->read(&frame, 0), FrameSource::Read::kEnd);
  EXPECT_EQ(source->no_frames_reason(),
            path +
                ": no frames: 1 of 1 records could not be read; the first, record 1: "
                "truncated: the file ends at byte 60, inside its header (72 bytes at least)");
}

TEST_F(BlfLogFrameSourceTest, AReadErrorIsNotTheEndOfTheLog) {
  // Reading a directory through a file stream fails with EISDIR on the first read.
  auto in = std::make_unique<std::ifstream>(dir_, std::ios::binary);
  ASSERT_TRUE(in->is_open());
  BlfLogFrameSource source(std::move(in), "drive.blf");
  can::CanFrame frame;
  EXPECT_EQ(source.read(&frame, 0), FrameSource::Read::kEnd);
  EXPECT_EQ(source.problem(), "drive.blf: read error: Is a directory");
  EXPECT_EQ(source.stats().corrupt, 0u);  // a read error is no damage of the file
}

}  // namespace
}  // namespace vmass::runtime
