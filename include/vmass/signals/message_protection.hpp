// MessageProtection: the config's `can.e2e` section resolved against the DBC: which messages
// carry an alive counter and a checksum, and how they are checked (can/e2e.hpp).
//
//   can:
//     e2e:
//       invalid_after: 5               # consecutive failed frames that make a message invalid
//       valid_after: 2                 # consecutive good frames that make it valid again
//       messages:
//         ESC_Speed:                   # a DBC message name
//           counter: ESC_Speed_Counter       # alive counter signal (optional)
//           max_counter_step: 1              # accepted increments 1..N (optional)
//           checksum: ESC_Speed_Checksum     # checksum signal (optional; one of the two)
//           algorithm: xor                   # crc8_sae_j1850 | xor | additive | a registered one
//           data_id: id_low_byte             # optional: a number 0..0xFFFF (0x.. hex too), or
//                                            #   id_low_byte: the CAN id's low byte
//           bytes: [0, 5]                    # covered payload bytes, first and last; default:
//                                            #   every byte but the checksum signal's
//
// vmass-sim's population writes such a bus: `counter` in byte 7's low nibble, `checksum` in
// byte 6 = XOR of the id's low byte and bytes 0..5, i.e. {algorithm: xor, data_id:
// id_low_byte, bytes: [0, 5]}.
//
// Errors name file, line and key (unknown message or signal, a signed or float counter, an
// unknown algorithm, a checksum signal narrower than the algorithm needs, bytes outside the
// message). Configuration time only; a MessageProtection is a plain value.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vmass/can/decoder.hpp"
#include "vmass/can/e2e.hpp"

namespace vmass::signals {

struct ProtectedMessage {
  int message = -1;  ///< index in the decoder's database
  can::E2eProfile profile;
};

struct MessageProtection {
  int invalid_after = 5;
  int valid_after = 2;
  std::vector<ProtectedMessage> messages;

  /// The profile of a message, or nullptr when it is not protected.
  const can::E2eProfile* find(int message) const;
};

/// Parses `can.e2e` (the node may be null: nothing protected). "" and *out, or
/// "file:line: can.e2e.key: message".
std::string parse_message_protection(const YAML::Node& e2e, const std::string& file,
                                     const can::Decoder& decoder, const std::string& dbc_name,
                                     MessageProtection* out);

}  // namespace vmass::signals
