// InterfaceSelection: one interface of a multi-interface CAN log, chosen by its name (the
// tools' --interface can1). A candump -l log names each frame's interface; ASC and TRC channel
// N, MDF4 bus N and BLF channel N are interface can<N-1> (docs/formats.md). The frames of the
// other interfaces are skipped and counted per interface, so that a name the log does not have
// is answered with those it has:
//     "no frame on interface can2; the log has can0 (12034 frames), can1 (8800 frames)"
// LogFrameSource applies it to every format (log_frame_source.hpp).
//
// Thread-safety: one reading thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vmass::runtime {

class InterfaceSelection {
 public:
  /// The longest interface name: IFNAMSIZ - 1, as Linux names network interfaces.
  static constexpr std::size_t kMaxNameBytes = 15;
  /// Interfaces the skipped frames are counted for one by one (the others together).
  static constexpr std::size_t kMaxCountedInterfaces = 32;

  /// "" when `name` is an interface name (1 to 15 of A-Z a-z 0-9 _ . -), else why not.
  static std::string name_error(std::string_view name);

  /// Selects the interface `name` (name_error(name) must be "").
  explicit InterfaceSelection(std::string name) : name_(std::move(name)) {}

  /// True when a frame on `interface` is the selected interface's; false (counted) when it is
  /// another's, to be skipped.
  bool take(std::string_view interface);

  const std::string& name() const { return name_; }
  /// Frames of other interfaces skipped so far.
  std::uint64_t skipped() const { return skipped_; }
  /// "no frame on interface can2; the log has can0 (12034 frames), can1 (8800 frames)", the
  /// interfaces in the order the log gave them ("the log has no frame" when it had none).
  std::string none_taken_reason() const;

 private:
  struct Other {
    std::string name;
    std::uint64_t frames = 0;
  };
  std::string name_;
  std::vector<Other> others_;    ///< the first kMaxCountedInterfaces others, by first frame
  std::uint64_t skipped_ = 0;    ///< frames of every other interface
  std::uint64_t uncounted_ = 0;  ///< frames of the others beyond kMaxCountedInterfaces
};

}  // namespace vmass::runtime
