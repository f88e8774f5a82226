// DBC parser: every statement form, real files' deviations (tolerant and strict), malformed input.
#include <gtest/gtest.h>

#include <string>

#include "vmass/can/dbc.hpp"

namespace vmass::can {
namespace {

const std::string kDataDir = VMASS_TEST_DATA_DIR;

bool has_diagnostic(const DbcParseResult& r, Severity sev, int line, const std::string& text) {
  for (const auto& d : r.diagnostics) {
    if (d.severity == sev && d.line == line && d.message.find(text) != std::string::npos) {
      return true;
    }
  }
  return false;
}

std::string dump(const DbcParseResult& r) {
  std::string s;
  for (const auto& d : r.diagnostics) s += d.to_string() + "\n";
  return s;
}

const char* kFull = R"(VERSION "1.2"

NS_ :
	NS_DESC_
	CM_
	SG_MUL_VAL_

BS_:

BU_: ECU1 ECU2
VAL_TABLE_ Gears 0 "P" 1 "R" 2 "N" 3 "D" ;

BO_ 256 Engine: 8 ECU1
 SG_ Speed : 0|16@1+ (0.01,0) [0|655.35] "km/h" ECU2
 SG_ Temp : 23|8@0- (0.5,-40) [-104|23.5] "degC" ECU2,ECU1
 SG_ Gear : 40|3@1+ (1,0) [0|0] "" Vector__XXX

BO_ 2147484672 ExtMsg: 64 ECU2
 SG_ Mode M : 0|8@1+ (1,0) [0|255] "" ECU1
 SG_ SubMode m1M : 8|8@1+ (1,0) [0|255] "" ECU1
 SG_ A m0 : 16|16@1- (1,0) [0|0] "" ECU1
 SG_ B m1 : 16|32@1+ (1,0) [0|0] "" ECU1
 SG_ C m2 : 32|32@1+ (1,0) [0|0] "" ECU1
 SG_ F32 : 64|32@1- (1,0) [0|0] "" ECU1
 SG_ F64 : 128|64@1- (1,0) [0|0] "" ECU1
 SG_ Tail : 511|1@1+ (1,0) [0|0] "" ECU1

BO_ 3221225472 VECTOR__INDEPENDENT_SIG_MSG: 0 Vector__XXX
 SG_ Orphan : 0|8@1+ (1,0) [0|0] "" Vector__XXX

CM_ "database comment";
CM_ BU_ ECU1 "the engine controller";
CM_ BO_ 256 "engine status";
CM_ SG_ 256 Speed "vehicle speed
over two lines with a \"quote\"";
CM_ SG_ 3221225472 Orphan "skipped with its message";
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000;
BA_DEF_ BO_ "VFrameFormat" ENUM "StandardCAN","ExtendedCAN","reserved","StandardCAN_FD","ExtendedCAN_FD";
BA_DEF_ SG_ "GenSigStartValue" FLOAT 0 1e+09;
BA_DEF_  "BusType" STRING ;
BA_DEF_DEF_ "GenMsgCycleTime" 100;
BA_DEF_DEF_ "VFrameFormat" "StandardCAN";
BA_DEF_DEF_ "BusType" "CAN";
BA_ "BusType" "CAN FD";
BA_ "GenMsgCycleTime" BO_ 256 20;
BA_ "VFrameFormat" BO_ 2147484672 4;
BA_ "GenSigStartValue" SG_ 256 Speed 0;
VAL_ 256 Gear 0 "P" 1 "R" 2 "N" 3 "D" -1 "invalid" ;
SIG_VALTYPE_ 2147484672 F32 : 1;
SIG_VALTYPE_ 2147484672 F64: 2;
SG_MUL_VAL_ 2147484672 SubMode Mode 1-1;
SG_MUL_VAL_ 2147484672 A Mode 0-0;
SG_MUL_VAL_ 2147484672 B SubMode 1-1, 5-7;
SG_MUL_VAL_ 2147484672 C SubMode 2-2;
)";

TEST(DbcParser, ParsesEveryStatementForm) {
  const DbcParseResult r = parse_dbc(kFull, "full.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.warning_count(), 0) << dump(r);
  const Database& db = r.database;
  EXPECT_EQ(db.version, "1.2");
  EXPECT_EQ(db.nodes, (std::vector<std::string>{"ECU1", "ECU2"}));
  EXPECT_EQ(db.comment, "database comment");
  ASSERT_EQ(db.messages.size(), 2u);  // VECTOR__INDEPENDENT_SIG_MSG left out
  ASSERT_EQ(db.value_tables.size(), 1u);
  EXPECT_EQ(db.value_tables[0].values.size(), 4u);

  const Message& eng = db.messages[0];
  EXPECT_EQ(eng.id, 256u);
  EXPECT_FALSE(eng.extended);
  EXPECT_EQ(eng.length, 8);
  EXPECT_EQ(eng.transmitter, "ECU1");
  EXPECT_EQ(eng.comment, "engine status");
  EXPECT_EQ(eng.cycle_time_ms, 20);
  EXPECT_FALSE(eng.fd);
  ASSERT_EQ(eng.signals.size(), 3u);
  const Signal& speed = eng.signals[0];
  EXPECT_EQ(speed.start_bit, 0);
  EXPECT_EQ(speed.length, 16);
  EXPECT_EQ(speed.byte_order, ByteOrder::kIntel);
  EXPECT_FALSE(speed.is_signed);
  EXPECT_DOUBLE_EQ(speed.factor, 0.01);
  EXPECT_DOUBLE_EQ(speed.maximum, 655.35);
  EXPECT_TRUE(speed.has_range);
  EXPECT_EQ(speed.unit, "km/h");
  EXPECT_EQ(speed.comment, "vehicle speed\nover two lines with a \"quote\"");
  const Signal& temp = eng.signals[1];
  EXPECT_EQ(temp.byte_order, ByteOrder::kMotorola);
  EXPECT_TRUE(temp.is_signed);
  EXPECT_DOUBLE_EQ(temp.offset, -40.0);
  EXPECT_EQ(temp.receivers, (std::vector<std::string>{"ECU2", "ECU1"}));
  const Signal& gear = eng.signals[2];
  EXPECT_FALSE(gear.has_range);
  ASSERT_EQ(gear.values.size(), 5u);
  EXPECT_EQ(gear.values[4].value, -1);
  EXPECT_EQ(gear.values[3].text, "D");

  const Message& ext = db.messages[1];
  EXPECT_TRUE(ext.extended);
  EXPECT_EQ(ext.id, 0x400u);
  EXPECT_EQ(ext.length, 64);
  EXPECT_TRUE(ext.fd);
  EXPECT_EQ(ext.cycle_time_ms, 100);  // BA_DEF_DEF_
  ASSERT_EQ(ext.signals.size(), 8u);
  EXPECT_TRUE(ext.signals[0].is_multiplexor);
  EXPECT_EQ(ext.signals[0].mux_parent, -1);
  EXPECT_TRUE(ext.signals[1].is_multiplexor);
  EXPECT_EQ(ext.signals[1].mux_parent, 0);
  EXPECT_EQ(ext.signals[2].mux_parent, 0);  // A m0, via SG_MUL_VAL_ on Mode
  EXPECT_EQ(ext.signals[3].mux_parent, 1);  // B switches on SubMode
  ASSERT_EQ(ext.signals[3].mux_ranges.size(), 2u);
  EXPECT_EQ(ext.signals[3].mux_ranges[1].lo, 5u);
  EXPECT_EQ(ext.signals[3].mux_ranges[1].hi, 7u);
  EXPECT_EQ(ext.signals[5].value_type, ValueType::kFloat32);
  EXPECT_EQ(ext.signals[6].value_type, ValueType::kFloat64);
  EXPECT_EQ(db.find_message(0x400, true), 1);
  EXPECT_EQ(db.find_message(0x400, false), -1);
  EXPECT_EQ(db.find_message("Engine"), 0);
}

TEST(DbcParser, SimpleMultiplexingAttachesToTheSwitch) {
  const char* text =
      "BO_ 10 M: 8 X\n"
      " SG_ Sw M : 0|4@1+ (1,0) [0|0] \"\" X\n"
      " SG_ P0 m0: 8|8@1+ (1,0) [0|0] \"\" X\n"
      " SG_ P12 m12 : 8|16@1+ (1,0) [0|0] \"\" X\n";
  const DbcParseResult r = parse_dbc(text, "mux.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  const Message& m = r.database.messages[0];
  EXPECT_EQ(m.signals[1].mux_parent, 0);
  ASSERT_EQ(m.signals[2].mux_ranges.size(), 1u);
  EXPECT_EQ(m.signals[2].mux_ranges[0].lo, 12u);
  EXPECT_EQ(*m.signals[2].mux_value, 12u);
}

TEST(DbcParser, CrlfAndByteOrderMark) {
  const std::string text =
      "\xEF\xBB\xBFVERSION \"\"\r\n\r\nBU_: A\r\nBO_ 1 M: 2 A\r\n SG_ S : 0|8@1+ (1,0) [0|0] \"u\" "
      "A\r\n\r\nCM_ SG_ 1 S \"two\r\nlines\";\r\nVAL_ 1 S 1 \"one\" ;\r\n";
  const DbcParseResult r = parse_dbc(text, "crlf.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.warning_count(), 0) << dump(r);
  EXPECT_EQ(r.database.messages[0].signals[0].comment, "two\nlines");
  EXPECT_EQ(r.database.messages[0].signals[0].receivers, std::vector<std::string>{"A"});
}

// Each deviation real files contain: loaded as meant, a warning naming file:line.
const char* kDeviations =
    "BU_: A\n"                                           // 1
    "BO_ 2365480958 Ext: 8 A\n"                          // 2 (bit 31: fine)
    " SG_ 1st : 0|8@1+ (1,0) [0|0] \"\xB0/s\" A\n"       // 3 digit name, cp1252 unit
    "BO_ 419364350 NoBit31: 8 A\n"                       // 4 > 0x7FF without bit 31
    " SG_ S : 0|8@1+ (1,0) [0|0] \"\" A\n"               // 5
    "BO_ 1073743490 Bit30: 8 A\n"                        // 6 bit 30 (Toyota)
    " SG_ T : 0|8@1+ (1,0) [0|0] \"\" A\n"               // 7
    "VAL_ 419364350 S 0 \"off\" 1 \"on\"\n"              // 8 VAL_ without ;
    "CM_ 419364350 S \"signal comment without SG_\";\n"  // 9 CM_ without keyword
    "CM_ 419364350 \"message comment without BO_\";\n"   // 10
    "FOO_ bar baz\n"                                     // 11 unknown keyword
    "CM_ SG_ 419364350 Missing \"no such signal\";\n";   // 12

TEST(DbcParser, ToleratesRealFileDeviationsWithWarnings) {
  const DbcParseResult r = parse_dbc(kDeviations, "dev.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  const Database& db = r.database;
  ASSERT_EQ(db.messages.size(), 3u);
  EXPECT_TRUE(db.messages[0].extended);
  EXPECT_EQ(db.messages[0].id, 2365480958u & 0x1FFFFFFFu);
  EXPECT_EQ(db.messages[0].signals[0].name, "1st");
  EXPECT_EQ(db.messages[0].signals[0].unit, "\xC2\xB0/s");  // cp1252 degree sign as UTF-8
  EXPECT_TRUE(db.messages[1].extended);
  EXPECT_EQ(db.messages[1].id, 419364350u);
  EXPECT_FALSE(db.messages[2].extended);
  EXPECT_EQ(db.messages[2].id, 0x682u);
  EXPECT_EQ(db.messages[1].signals[0].values.size(), 2u);
  EXPECT_EQ(db.messages[1].signals[0].comment, "signal comment without SG_");
  EXPECT_EQ(db.messages[1].comment, "message comment without BO_");

  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 3, "begins with a digit")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 3, "cp1252")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 4, "above 0x7FF without bit 31")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 6, "bits 29-30")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 8, "VAL_ without ';'")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 9, "CM_ without object keyword")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 10, "CM_ without object keyword")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 11, "unknown keyword 'FOO_'")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 12, "unknown signal Missing")) << dump(r);
  EXPECT_EQ(r.warning_count(), 9) << dump(r);
  EXPECT_EQ(r.diagnostics[0].to_string().substr(0, 8), "dev.dbc:");
}

TEST(DbcParser, StrictModeTurnsDeviationsIntoErrors) {
  DbcParseOptions strict;
  strict.strict = true;
  const DbcParseResult r = parse_dbc(kDeviations, "dev.dbc", strict);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.error_count(), 9) << dump(r);
  EXPECT_EQ(r.warning_count(), 0);
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 8, "VAL_ without ';'")) << dump(r);
}

TEST(DbcParser, MalformedInputNamesLineColumnAndExpectation) {
  const DbcParseResult r =
      parse_dbc("BO_ 1 M: 8 A\n SG_ S : 0|8@2+ (1,0) [0|0] \"\" A\n", "bad.dbc");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.diagnostics.size(), 1u);
  const DbcDiagnostic& d = r.diagnostics[0];
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.column, 14);
  EXPECT_NE(d.message.find("expected byte order"), std::string::npos) << d.message;
  EXPECT_EQ(d.to_string().rfind("bad.dbc:2:14: error: expected byte order", 0), 0u)
      << d.to_string();

  const DbcParseResult r2 = parse_dbc("BO_ 1 M: 8 A\n SG_ S : 0|8@1+ (1;0) [0|0] \"\" A\n", "x");
  ASSERT_EQ(r2.diagnostics.size(), 1u);
  EXPECT_NE(r2.diagnostics[0].message.find("expected ','"), std::string::npos);
  EXPECT_EQ(r2.diagnostics[0].line, 2);

  const DbcParseResult r3 = parse_dbc("CM_ BO_ 1 \"never closed;\nBO_ 1 M: 8 A\n", "x");
  ASSERT_EQ(r3.diagnostics.size(), 1u);
  EXPECT_NE(r3.diagnostics[0].message.find("never closed"), std::string::npos);
  EXPECT_EQ(r3.diagnostics[0].line, 1);
  EXPECT_EQ(r3.diagnostics[0].column, 11);

  const DbcParseResult r4 = parse_dbc(" SG_ S : 0|8@1+ (1,0) [0|0] \"\" A\n", "x");
  ASSERT_FALSE(r4.ok());
  EXPECT_NE(r4.diagnostics[0].message.find("SG_ outside a BO_"), std::string::npos);

  const DbcParseResult r5 = parse_dbc("BO_ 1 M: 8 A\n SG_ S : 0|8@1+ (1,0) [0|x] \"\" A\n", "x");
  ASSERT_FALSE(r5.ok());
  EXPECT_NE(r5.diagnostics[0].message.find("expected maximum"), std::string::npos);
}

TEST(DbcParser, SignalsNotFittingTheirMessageAreErrorsNamingTheSignal) {
  const char* text =
      "BO_ 1 M: 2 A\n"
      " SG_ Ok : 0|16@1+ (1,0) [0|0] \"\" A\n"
      " SG_ TooFar : 9|8@1+ (1,0) [0|0] \"\" A\n"
      " SG_ Zero : 0|0@1+ (1,0) [0|0] \"\" A\n"
      " SG_ Huge : 0|65@1+ (1,0) [0|0] \"\" A\n"
      " SG_ MotoTooFar : 15|16@0+ (1,0) [0|0] \"\" A\n"  // MSB in byte 1: LSB lands in byte 2
      " SG_ MotoOk : 7|16@0+ (1,0) [0|0] \"\" A\n"
      "BO_ 2 Big: 65 A\n";
  const DbcParseResult r = parse_dbc(text, "fit.dbc");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 3, "signal TooFar of message M")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 4, "signal Zero of message M: length 0"));
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 5, "signal Huge of message M: length 65"));
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 6, "signal MotoTooFar")) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 8, "at most 64")) << dump(r);
  // The bad signals are left out; the rest of the file stays usable.
  ASSERT_EQ(r.database.messages[0].signals.size(), 2u);
  EXPECT_EQ(r.database.messages[0].signals[1].name, "MotoOk");
}

TEST(DbcParser, MultiplexedSignalWithoutSwitchIsAnError) {
  const DbcParseResult r = parse_dbc(
      "BO_ 1 M: 8 A\n SG_ S m3 : 0|8@1+ (1,0) [0|0] \"\" A\n SG_ T : 8|8@1+ (1,0) [0|0] \"\" A\n",
      "mux.dbc");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 2, "no multiplexor")) << dump(r);
  EXPECT_EQ(r.database.messages[0].signals.size(), 1u);
}

TEST(DbcParser, OverlapsAreReportedUnlessTheMultiplexorSeparatesThem) {
  const DbcParseResult r = parse_dbc(
      "BO_ 1 M: 8 A\n"
      " SG_ Sw M : 0|8@1+ (1,0) [0|0] \"\" A\n"
      " SG_ P m0 : 8|16@1+ (1,0) [0|0] \"\" A\n"
      " SG_ Q m1 : 8|16@1+ (1,0) [0|0] \"\" A\n"  // same bits as P, other mux value: fine
      " SG_ R : 23|8@0+ (1,0) [0|0] \"\" A\n"     // byte 2: overlaps P and Q
      " SG_ S : 32|8@1+ (1,0) [0|0] \"\" A\n",
      "ov.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_EQ(r.warning_count(), 1) << dump(r);
  EXPECT_TRUE(has_diagnostic(r, Severity::kWarning, 5, "signal R of message M overlaps"));
}

TEST(DbcParser, DuplicateIdsAreErrors) {
  const DbcParseResult r = parse_dbc("BO_ 5 A: 8 X\nBO_ 5 B: 8 X\n", "dup.dbc");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_diagnostic(r, Severity::kError, 2, "same id as A")) << dump(r);
}

TEST(DbcParser, NumbersAreLocaleFree) {
  // 1e+09 style exponents, leading '+', integers written as decimals.
  const DbcParseResult r =
      parse_dbc("BO_ 1 M: 8 A\n SG_ S : 0|8@1+ (+2.5e-1,-1E2) [0|1e+09] \"\" A\n", "n.dbc");
  ASSERT_TRUE(r.ok()) << dump(r);
  EXPECT_DOUBLE_EQ(r.database.messages[0].signals[0].factor, 0.25);
  EXPECT_DOUBLE_EQ(r.database.messages[0].signals[0].offset, -100.0);
  EXPECT_DOUBLE_EQ(r.database.messages[0].signals[0].maximum, 1e9);
}

TEST(DbcParser, MissingFileIsOneError) {
  const DbcParseResult r = load_dbc_file("/nonexistent/x.dbc");
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_NE(r.diagnostics[0].message.find("cannot open"), std::string::npos);
}

struct RealFile {
  const char* name;
  std::size_t messages;
  std::size_t signals;  // as cantools 45.1 counts them (strict=False) where it loads the file
  int errors;
};

class RealDbc : public ::testing::TestWithParam<RealFile> {};

TEST_P(RealDbc, LoadsWithExpectedCounts) {
  const RealFile f = GetParam();
  const DbcParseResult r = load_dbc_file(kDataDir + "/dbc/" + f.name);
  EXPECT_EQ(r.error_count(), f.errors) << dump(r);
  std::size_t signals = 0;
  for (const auto& m : r.database.messages) signals += m.signals.size();
  EXPECT_EQ(r.database.messages.size(), f.messages);
  EXPECT_EQ(signals, f.signals);
}

INSTANTIATE_TEST_SUITE_P(OpenDbc, RealDbc,
                         ::testing::Values(
                             // Four signals of MRR_Detection_022 lie beyond its 24-byte payload:
                             // errors, left out (cantools counts them: 1854).
                             RealFile{"FORD_CADS_64.dbc", 80, 1850, 4},
                             RealFile{"gm_global_a_high_voltage_management.dbc", 12, 125, 0},
                             RealFile{"hyundai_2015_mcan.dbc", 170, 1180, 0},
                             RealFile{"tesla_model3_vehicle.dbc", 11, 209, 0},
                             RealFile{"toyota_2017_ref_pt.dbc", 143, 1315, 0},
                             RealFile{"toyota_prius_2010_pt.dbc", 26, 78, 0},
                             RealFile{"vw_mqb.dbc", 113, 1348, 0}),
                         [](const ::testing::TestParamInfo<RealFile>& p) {
                           std::string n = p.param.name;
                           for (char& c : n) {
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return n;
                         });

TEST(RealDbcDetails, FactsCheckedAgainstTheFiles) {
  const DbcParseResult vw = load_dbc_file(kDataDir + "/dbc/vw_mqb.dbc");
  const int lwi = vw.database.find_message("LWI_01");
  ASSERT_GE(lwi, 0);
  const Message& m = vw.database.messages[static_cast<std::size_t>(lwi)];
  EXPECT_EQ(m.id, 134u);
  const Signal& s = m.signals[static_cast<std::size_t>(m.find_signal("LWI_Lenkradwinkel"))];
  EXPECT_EQ(s.start_bit, 16);
  EXPECT_EQ(s.length, 13);
  EXPECT_DOUBLE_EQ(s.factor, 0.1);
  EXPECT_EQ(s.unit, "Unit_DegreOfArc");
  // A comment spanning four lines with UTF-8 umlauts.
  const int kbi = vw.database.find_message(1720, false);
  ASSERT_GE(kbi, 0);
  const Message& k = vw.database.messages[static_cast<std::size_t>(kbi)];
  const Signal& ru =
      k.signals[static_cast<std::size_t>(k.find_signal("KBI_Reifenumfang_Sekundaer"))];
  EXPECT_NE(ru.comment.find("\nPrim\xC3\xA4rachse: KBI_Reifenumfang\n"), std::string::npos);
  // Comments naming signals the file does not define: warnings with their line.
  EXPECT_TRUE(has_diagnostic(vw, Severity::kWarning, 1630, "unknown signal ACC_Hold_Request"));
  // PLA_01 declares signals on the same bits (cantools cannot decode that message).
  EXPECT_TRUE(has_diagnostic(vw, Severity::kWarning, 91,
                             "PLA_Bremsverzoegerung of message PLA_01 overlaps signal "
                             "PLA_Bremsmoment"));
  EXPECT_TRUE(has_diagnostic(vw, Severity::kWarning, 92, "PLA_Anf_Bremsverzoegerung"));
  // A 4-bit counter declared [0|255]: what its bits carry is [0|15] (a warning, also in strict).
  EXPECT_TRUE(has_diagnostic(vw, Severity::kWarning, 911,
                             "declared range [0|255] lies outside what its 4 unsigned bits carry "
                             "[0|15]"));
  EXPECT_EQ(vw.warning_count(), 20) << dump(vw);

  const DbcParseResult toyota = load_dbc_file(kDataDir + "/dbc/toyota_2017_ref_pt.dbc");
  EXPECT_EQ(toyota.warning_count(), 32);
  EXPECT_TRUE(has_diagnostic(toyota, Severity::kWarning, 387, "0x40140639"));

  // Hyundai's only id with bit 31 is VECTOR__INDEPENDENT_SIG_MSG (0xC0000000): left out.
  const DbcParseResult hy = load_dbc_file(kDataDir + "/dbc/hyundai_2015_mcan.dbc");
  int extended = 0;
  for (const auto& msg : hy.database.messages) extended += msg.extended ? 1 : 0;
  EXPECT_EQ(extended, 0);
  EXPECT_EQ(hy.database.find_message("VECTOR__INDEPENDENT_SIG_MSG"), -1);

  const DbcParseResult ford = load_dbc_file(kDataDir + "/dbc/FORD_CADS_64.dbc");
  const int f34 = ford.database.find_message(34, false);
  ASSERT_GE(f34, 0);
  EXPECT_EQ(ford.database.messages[static_cast<std::size_t>(f34)].cycle_time_ms, 1000);
  int fd = 0;
  for (const auto& msg : ford.database.messages) fd += msg.fd ? 1 : 0;
  EXPECT_GT(fd, 0);
}

}  // namespace
}  // namespace vmass::can
