#pragma once

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "cover/config/param_fields.hpp"

namespace cover::test {

// The shipped-file test of a parameter struct declared once (config/param_fields.hpp):
// every field is written in the file's `section` (so the file documents all of them) and
// loads to the struct's default. `shipped` is what the struct's own loader made of it.
template <typename Params>
void expect_shipped_file_holds_defaults(const Params& shipped, const std::string& path,
                                        const std::string& section) {
  const YAML::Node node = YAML::LoadFile(path)[section];
  ASSERT_TRUE(node && node.IsMap()) << path << " has no section " << section;
  for (const std::string& key : config::field_keys<Params>()) {
    EXPECT_TRUE(node[key]) << path << ": " << section << "." << key
                           << " is a field but the shipped file does not write it";
  }
  const auto defaults = config::field_values(Params{});
  const auto values = config::field_values(shipped);
  ASSERT_EQ(values.size(), defaults.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(values[i].second, defaults[i].second)
        << path << ": " << section << "." << values[i].first << " differs from its default";
  }
}

}  // namespace cover::test
