// docs/formats.md against the loaders: the configuration block it shows is a config the loaders
// accept as it stands (every key it documents exists), and every key the loaders read is in it
// (no key goes undocumented). The loaders' keys are the string literals they pass to
// YamlReader::read / require / child / raw / has.
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "vmass/config/config.hpp"
#include "vmass/service/service_config.hpp"

namespace vmass {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The first ```yaml block of docs/formats.md.
std::string documented_config() {
  const std::string doc = read_file(VMASS_SOURCE_DIR "/docs/formats.md");
  const std::string open = "```yaml\n";
  const std::size_t begin = doc.find(open);
  const std::size_t end = doc.find("```", begin + open.size());
  if (begin == std::string::npos || end == std::string::npos) return "";
  return doc.substr(begin + open.size(), end - begin - open.size());
}

/// The keys the given loader sources read: calls with a literal key, and the entries of field
/// tables ({"key", &Struct::member, ...}).
std::set<std::string> loader_keys(std::initializer_list<const char*> files) {
  std::set<std::string> keys;
  const std::regex call(
      R"re(\b(?:read|require|child|raw|has)\("([a-z_0-9]+)"|\{"([a-z_0-9]+)", &[A-Za-z]+::)re");
  for (const char* file : files) {
    const std::string source = read_file(std::string(VMASS_SOURCE_DIR) + file);
    EXPECT_FALSE(source.empty()) << file;
    for (std::sregex_iterator it(source.begin(), source.end(), call), end; it != end; ++it) {
      keys.insert((*it)[1].matched ? (*it)[1].str() : (*it)[2].str());
    }
  }
  return keys;
}

TEST(FormatsDoc, TheDocumentedConfigLoadsAsItStands) {
  const std::string text = documented_config();
  ASSERT_FALSE(text.empty()) << "no ```yaml block in docs/formats.md";
  const ConfigLoad loaded = load_config_text(text, "docs/formats.md");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const service::ServiceSettingsLoad settings = service::load_service_settings(*loaded.config);
  EXPECT_TRUE(settings.ok()) << settings.error;
}

/// Keys of the loaders whose sections docs/formats.md documents (the can.inputs entries are
/// documented in docs/signal-mapping.md).
std::set<std::string> loader_keys() {
  return loader_keys({"/src/config/config.cpp", "/include/vmass/config/suspension_section.hpp",
                      "/src/service/service_config.cpp"});
}

TEST(FormatsDoc, EveryKeyTheLoadersReadIsDocumented) {
  const std::string text = documented_config();
  const std::set<std::string> keys = loader_keys();
  ASSERT_GT(keys.size(), 80u) << "the loaders' keys were not found in their sources";
  for (const std::string& key : keys) {
    const std::regex documented("(^|\n) *" + key + ":");
    EXPECT_TRUE(std::regex_search(text, documented))
        << key << " is read by the loader but not documented in docs/formats.md";
  }
}

}  // namespace
}  // namespace vmass

namespace vmass {
namespace {

// docs/signal-mapping.md documents the can: section: every key its loaders read (can.inputs,
// can.e2e, can.plausibility) appears there as "key:".
TEST(FormatsDoc, EveryCanKeyIsInTheSignalMappingDoc) {
  const std::string doc = read_file(VMASS_SOURCE_DIR "/docs/signal-mapping.md");
  const std::set<std::string> keys =
      loader_keys({"/src/signals/signal_mapping.cpp", "/src/signals/message_protection.cpp",
                   "/src/signals/plausibility_params.cpp"});
  ASSERT_GT(keys.size(), 30u) << "the can: loaders' keys were not found in their sources";
  for (const std::string& key : keys) {
    const std::regex documented("[ {,]" + key + ":");
    EXPECT_TRUE(std::regex_search(doc, documented))
        << key << " is read by the can: loaders but not documented in docs/signal-mapping.md";
  }
}

}  // namespace
}  // namespace vmass
