#pragma once
// What the tests of a launch file's plan share (tests/launch, and the recorder's and the
// live view's launch keys in tests/mcap and tests/foxglove): a launch file from YAML text,
// and the launcher's options for a run folder.
#include <yaml-cpp/yaml.h>

#include <string>

#include "cover/launch/launch_file.hpp"
#include "cover/launch/launch_plan.hpp"

namespace cover::launch::testing {

// `yaml` as a launch file test.yaml in /launch.
inline LaunchFile parse(const std::string& yaml) {
  return LaunchFile::parse(YAML::Load(yaml), "test.yaml", "/launch");
}

// Options of a run into `run_dir`, on domain 7.
inline LaunchOptions options_in(const std::string& run_dir) {
  LaunchOptions options;
  options.run_dir = run_dir;
  options.domain_id = 7;
  return options;
}

}  // namespace cover::launch::testing
