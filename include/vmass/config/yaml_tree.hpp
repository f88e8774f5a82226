// Checks of a parsed YAML tree that yaml-cpp leaves to its user:
//
//   duplicate_key_error(root, file)   "file:line: a.b: duplicate key (first at line N)" for the
//                                     first map key written twice anywhere in the tree, ""
//                                     when none is (yaml-cpp keeps both and looks up the first:
//                                     a silent "first wins" that the config must refuse); also
//                                     the error of a tree of more than 100,000 nodes once its
//                                     aliases are expanded (nested anchors: "billion laughs"),
//                                     or of more than 64 levels (an alias inside its own node)
//   line_of_key(root, "a.b[2]")       the line (1-based) of a dotted key, or of its deepest
//                                     existing parent; 0 when not even the first part exists;
//                                     for validation errors raised after parsing
//
// Configuration time only; reentrant.
#pragma once

#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

namespace vmass {

std::string duplicate_key_error(const YAML::Node& root, const std::string& file);
int line_of_key(const YAML::Node& root, std::string_view dotted_key);

}  // namespace vmass
