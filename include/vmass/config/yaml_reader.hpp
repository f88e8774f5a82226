// YamlReader: reads typed values out of a yaml-cpp node tree with errors that name the file,
// the line and the full key ("config.yaml:12: estimator.rls.forgetting_factor: expected a
// number, got 'abc'"), and that reject keys nobody read (typos must not be silently ignored).
//
// Used at configuration time only (it allocates and throws ConfigError internally; the public
// loaders turn that into a status). Not thread-safe.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace vmass {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class YamlReader {
 public:
  /// `node` must be a map (or null/absent, meaning all defaults); `path` is the dotted key
  /// prefix ("" at the top).
  YamlReader(YAML::Node node, std::string file, std::string path);

  bool has(const std::string& key) const;
  /// Read key into *out when present (else leave the default). Throws ConfigError.
  void read(const std::string& key, double* out);
  void read(const std::string& key, int* out);
  void read(const std::string& key, long* out);
  void read(const std::string& key, bool* out);
  void read(const std::string& key, std::string* out);
  void read(const std::string& key, std::vector<double>* out);
  void read(const std::string& key, std::vector<int>* out);
  /// Like read() but the key must be present.
  void require(const std::string& key, double* out);
  void require(const std::string& key, std::string* out);
  /// A nested map reader (absent: an empty reader, all defaults).
  YamlReader child(const std::string& key);
  /// The raw node of a key (marked as used), for sections parsed elsewhere.
  YAML::Node raw(const std::string& key);
  /// Throws ConfigError naming the first key that was never read.
  void reject_unknown_keys() const;

  /// "file:line: full.key: message"
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  std::string full_key(const std::string& key) const;
  const std::string& file() const { return file_; }

 private:
  YAML::Node value_node(const std::string& key) const;
  /// Throws when the key is there with a null value (`key:`, `key: ~`).
  void refuse_null(const std::string& key) const;
  int line_of(const YAML::Node& n) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::vector<std::string> used_;
};

}  // namespace vmass
