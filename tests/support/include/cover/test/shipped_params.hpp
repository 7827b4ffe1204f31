#pragma once

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "cover/config/param_fields.hpp"

namespace cover::test {

// The node at dotted `path` ("ugv_agent.imu_filter") under `root`; an undefined node when
// a step is missing or not a mapping. Recursive, not a loop: assigning a YAML::Node
// rebinds what it refers to, and would rewrite the document.
inline YAML::Node node_at(const YAML::Node& root, const std::string& path) {
  const std::size_t dot = path.find('.');
  if (!root.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node next = root[path.substr(0, dot)];  // const: a missing key is not created
  if (!next.IsDefined() || dot == std::string::npos) return next;
  return node_at(next, path.substr(dot + 1));
}

// The shipped file's `section` (dotted) writes every field of Params, sub-sections' fields
// by their dotted keys: the file documents all of them, and a field added to fields() fails
// here until it is shipped.
template <typename Params>
void expect_shipped_file_holds_every_field(const std::string& path, const std::string& section) {
  const YAML::Node node = node_at(YAML::LoadFile(path), section);
  ASSERT_TRUE(node.IsDefined() && node.IsMap()) << path << " has no section " << section;
  for (const std::string& key : config::field_keys<Params>()) {
    EXPECT_TRUE(node_at(node, key).IsDefined())
        << path << ": " << section << "." << key
        << " is a field but the shipped file does not write it";
  }
}

// The shipped-file test of a parameter struct whose shipped file states its defaults:
// every field is written in `section` and loads to the struct's default. `shipped` is what
// the struct's own loader made of the file.
template <typename Params>
void expect_shipped_file_holds_defaults(const Params& shipped, const std::string& path,
                                        const std::string& section) {
  expect_shipped_file_holds_every_field<Params>(path, section);
  const auto defaults = config::field_values(Params{});
  const auto values = config::field_values(shipped);
  ASSERT_EQ(values.size(), defaults.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(values[i].second, defaults[i].second)
        << path << ": " << section << "." << values[i].first << " differs from its default";
  }
}

}  // namespace cover::test
