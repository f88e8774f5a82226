// A small DBC for the signal-mapping tests: Intel and Motorola, signed and unsigned, a float32,
// a multiplexed extended-id message (one signal on two pages), units known, unknown and missing,
// ranges and cycle times.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::testing {

inline const char* kTestDbc = R"(VERSION ""

NS_ :

BS_:

BU_: ECU

BO_ 256 Speeds: 8 ECU
 SG_ SpeedKmh : 0|16@1+ (0.01,0) [0|300] "km/h" ECU
 SG_ SpeedMph : 16|16@1+ (0.01,0) [0|200] "mph" ECU
 SG_ Odd : 32|16@1+ (1,0) [0|0] "furlong/fortnight" ECU
 SG_ NoUnit : 48|16@1- (1,0) [0|0] "" ECU

BO_ 257 Torques: 8 ECU
 SG_ Front : 7|16@0- (0.5,0) [-10000|10000] "Nm" ECU
 SG_ Rear : 23|16@0- (0.5,0) [-10000|10000] "N*m" ECU
 SG_ Pressure : 32|16@1+ (1,0) [0|20000] "kPa" ECU

BO_ 258 Imu: 8 ECU
 SG_ AxG : 0|32@1- (1,0) [0|0] "g" ECU
 SG_ Yaw : 32|16@1- (0.01,0) [-100|100] "deg/s" ECU
 SG_ Steer : 48|16@1- (0.1,0) [-800|800] "deg" ECU

BO_ 2147484160 Level: 8 ECU
 SG_ Page M : 0|8@1+ (1,0) [0|0] "" ECU
 SG_ LevelRR m1 : 8|16@1- (0.01,0) [-300|300] "mm" ECU
 SG_ LevelFL m0 : 8|16@1- (0.01,0) [-300|300] "mm" ECU
 SG_ Gear m0 : 24|8@1- (1,0) [-1|8] "" ECU
 SG_ Shared m1 : 40|8@1- (1,0) [0|0] "" ECU

BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000;
BA_DEF_DEF_ "GenMsgCycleTime" 0;
BA_ "GenMsgCycleTime" BO_ 256 10;
BA_ "GenMsgCycleTime" BO_ 257 20;
BA_ "GenMsgCycleTime" BO_ 2147484160 100;
SIG_VALTYPE_ 258 AxG : 1;
SG_MUL_VAL_ 2147484160 Shared Page 1-2;
)";

inline std::shared_ptr<const can::Decoder> test_decoder() {
  can::DbcParseResult r = can::parse_dbc(kTestDbc, "test.dbc");
  EXPECT_TRUE(r.ok());
  std::string error;
  std::optional<can::Decoder> d = can::Decoder::compile(std::move(r.database), &error);
  EXPECT_TRUE(d.has_value()) << error;
  return std::make_shared<const can::Decoder>(std::move(*d));
}

/// A frame of `message` with the given physical values (others 0), stamped time_us.
inline can::CanFrame make_frame(const can::Decoder& d, const std::string& message,
                                const std::map<std::string, double>& values, std::int64_t time_us) {
  const int m = d.find_message(message);
  EXPECT_GE(m, 0) << message;
  const can::Message& msg = d.database().messages[static_cast<std::size_t>(m)];
  double v[64] = {};
  for (const auto& [name, value] : values) {
    const int s = msg.find_signal(name);
    EXPECT_GE(s, 0) << name;
    v[s] = value;
  }
  can::CanFrame f;
  d.encode(m, v, &f);
  f.time_us = time_us;
  return f;
}

}  // namespace vmass::testing
