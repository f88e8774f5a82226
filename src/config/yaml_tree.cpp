#include "vmass/config/yaml_tree.hpp"

#include <charconv>
#include <map>

#include "vmass/io/excerpt.hpp"

namespace vmass {
namespace {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

/// Nodes the walk visits at most. An alias is a shared node that the walk visits once per
/// reference: nested anchors make a 2.6 kB text a tree of billions (the "billion laughs"), which
/// would take hours to walk. Real configs are a few hundred nodes.
constexpr long kMaxYamlNodes = 100000;

/// Depth-first; "" or the first duplicate's error, or the error of a tree too large to walk.
/// Depth is bounded by yaml-cpp's parser.
std::string find_duplicate(const YAML::Node& node, const std::string& file, const std::string& path,
                           long* visited) {
  if (++*visited > kMaxYamlNodes) {
    return file + ":" + std::to_string(node.Mark().line + 1) + ": " +
           io::excerpt(path.empty() ? std::string("(top)") : path) + ": the YAML holds more than " +
           std::to_string(kMaxYamlNodes) +
           " nodes once its aliases (*name) are expanded; a config has a few hundred";
  }
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string e =
          find_duplicate(node[i], file, path + "[" + std::to_string(i) + "]", visited);
      if (!e.empty()) return e;
    }
    return "";
  }
  if (!node.IsMap()) return "";
  std::map<std::string, int> first_line;
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("<complex key>");
    const int line = kv.first.Mark().line + 1;
    const auto [it, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      return file + ":" + std::to_string(line) + ": " + io::excerpt(join(path, key)) +
             ": duplicate key (first at line " + std::to_string(it->second) + ")";
    }
    const std::string e = find_duplicate(kv.second, file, join(path, key), visited);
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace

std::string duplicate_key_error(const YAML::Node& root, const std::string& file) {
  long visited = 0;
  return find_duplicate(root, file, "", &visited);
}

int line_of_key(const YAML::Node& root, std::string_view dotted_key) {
  // reset() rebinds a Node; assigning one would overwrite the tree it refers to.
  YAML::Node node;
  node.reset(root);
  int line = 0;
  std::size_t begin = 0;
  while (begin <= dotted_key.size()) {
    std::size_t end = dotted_key.find('.', begin);
    if (end == std::string_view::npos) end = dotted_key.size();
    const std::string_view part = dotted_key.substr(begin, end - begin);
    const std::size_t bracket = part.find('[');
    const std::string key(part.substr(0, bracket));
    const YAML::Node& here = node;  // const lookups: no zombie keys are added
    if (!here.IsMap() || !here[key]) return line;
    node.reset(here[key]);
    line = node.Mark().line + 1;
    if (bracket != std::string_view::npos) {  // "name[i]"
      std::size_t index = 0;
      const std::string_view digits = part.substr(bracket + 1);
      const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      const YAML::Node& list = node;
      if (r.ec != std::errc() || !list.IsSequence() || index >= list.size()) return line;
      node.reset(list[index]);
      line = node.Mark().line + 1;
    }
    begin = end + 1;
  }
  return line;
}

}  // namespace vmass
