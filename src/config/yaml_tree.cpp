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
/// Levels the walk descends at most. The parser bounds the nesting of the text, but an alias can
/// name the node it sits in (`&a [*a]`): a cycle, which no depth-first walk leaves. Real configs
/// are four levels deep.
constexpr int kMaxYamlDepth = 64;

struct Walk {
  const std::string& file;
  long visited = 0;
};

std::string too_large(const YAML::Node& node, const Walk& w, const std::string& path,
                      const std::string& what) {
  return w.file + ":" + std::to_string(node.Mark().line + 1) + ": " +
         io::excerpt(path.empty() ? std::string("(top)") : path) + ": " + what;
}

/// Depth-first; "" or the first duplicate's error, or the error of a tree too large or too deep
/// to walk.
std::string find_duplicate(const YAML::Node& node, Walk& w, const std::string& path, int depth) {
  if (++w.visited > kMaxYamlNodes) {
    return too_large(
        node, w, path,
        "the YAML holds more than " + std::to_string(kMaxYamlNodes) +
            " nodes once its aliases (*name) are expanded; a config has a few hundred");
  }
  if (depth > kMaxYamlDepth) {
    return too_large(node, w, path,
                     "nested more than " + std::to_string(kMaxYamlDepth) +
                         " levels (an alias inside the node it names?)");
  }
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string e =
          find_duplicate(node[i], w, path + "[" + std::to_string(i) + "]", depth + 1);
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
      return w.file + ":" + std::to_string(line) + ": " + io::excerpt(join(path, key)) +
             ": duplicate key (first at line " + std::to_string(it->second) + ")";
    }
    const std::string e = find_duplicate(kv.second, w, join(path, key), depth + 1);
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace

std::string duplicate_key_error(const YAML::Node& root, const std::string& file) {
  Walk w{file};
  return find_duplicate(root, w, "", 0);
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
