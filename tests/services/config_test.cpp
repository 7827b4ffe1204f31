#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <string>

#include "cover/config/state_dir.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/test/scoped_env.hpp"
#include "cover/test/scratch_dir.hpp"

using cover::config::ConfigError;
using cover::config::YamlReader;

namespace {
YAML::Node parse(const char* text) {
  return YAML::Load(text);
}
}  // namespace

TEST(YamlReader, DefaultsStandWhenKeysAreAbsent) {
  YamlReader reader(parse("{}"), "test");
  double rho = 512.0;
  reader.optional("rho", rho);
  EXPECT_EQ(rho, 512.0);
}

TEST(YamlReader, ReadsScalarsAndFixedVectors) {
  YamlReader reader(parse("{rho: 3.5, weights: [1, 2, 3]}"), "test");
  double rho = 0;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  reader.optional("rho", rho);
  reader.optional("weights", weights);
  EXPECT_EQ(rho, 3.5);
  EXPECT_EQ(weights, Eigen::Vector3d(1, 2, 3));
}

TEST(YamlReader, MissingRequiredKeyIsNamed) {
  YamlReader reader(parse("{a: 1}"), "planner.yaml:planner");
  int pieces = 0;
  try {
    reader.require("pieces", pieces);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("planner.yaml:planner"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("'pieces'"), std::string::npos);
  }
}

TEST(YamlReader, WrongTypeNamesTheKey) {
  YamlReader reader(parse("{pieces: many}"), "ctx");
  int pieces = 0;
  EXPECT_THROW(reader.optional("pieces", pieces), ConfigError);
  YamlReader vec_reader(parse("{w: [1, 2]}"), "ctx");
  Eigen::Vector3d w;
  EXPECT_THROW(vec_reader.optional("w", w), ConfigError);
}

TEST(YamlReader, UnknownKeyIsRejected) {
  YamlReader reader(parse("{vmax: 1.0, vmax_ms: 2.0}"), "ctx");
  double vmax = 0;
  reader.optional("vmax", vmax);
  try {
    reader.reject_unknown_keys();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("vmax_ms"), std::string::npos);
  }
}

TEST(YamlReader, ChildMappingsCarryTheirPath) {
  YamlReader reader(parse("{sampc: {horizon: x}}"), "file");
  auto child = reader.child("sampc");
  int horizon = 0;
  try {
    child.optional("horizon", horizon);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("file.sampc.horizon"), std::string::npos);
  }
}

TEST(YamlFile, MissingFileAndSyntaxErrorAreClear) {
  EXPECT_THROW(cover::config::load_yaml_file("/nonexistent/cover.yaml"), ConfigError);
}

TEST(YamlFile, OpenSectionChecksTheTopLevel) {
  const std::string path = cover::test::scratch_path("section.yaml");
  std::ofstream(path) << "planner:\n  rho: 2\nplaner:\n  rho: 3\n";
  EXPECT_THROW(cover::config::open_section(path, "planner", false), ConfigError);  // typo'd key
  std::ofstream(path) << "planner:\n  rho: 2\n";
  auto reader = cover::config::open_section(path, "planner", false);
  double rho = 0;
  reader.optional("rho", rho);
  EXPECT_EQ(rho, 2.0);
  EXPECT_THROW(cover::config::open_section(path, "sampc", true), ConfigError);
  EXPECT_THROW(cover::config::open_section(path + ".missing", "x", false), ConfigError);
}

// From memory (what the fuzz harnesses and from_yaml take): the same checks, the source named.
TEST(YamlText, ParsesFromMemoryAndNamesTheSource) {
  try {
    cover::config::parse_yaml("planner: [1, 2", "input.yaml");
    FAIL() << "a syntax error was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("input.yaml: YAML syntax error at line"),
              std::string::npos)
        << e.what();
  }
  const YAML::Node document = cover::config::parse_yaml("planner:\n  rho: 2\n", "input.yaml");
  auto reader = cover::config::open_section(document, "input.yaml", "planner", true);
  double rho = 0;
  reader.optional("rho", rho);
  EXPECT_EQ(rho, 2.0);
  try {
    cover::config::open_section(document, "input.yaml", "sampc", true);
    FAIL() << "a missing section was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("input.yaml: missing section 'sampc'"), std::string::npos)
        << e.what();
  }
  const YAML::Node typo = cover::config::parse_yaml("planner: {}\nplaner: {}\n", "input.yaml");
  EXPECT_THROW(cover::config::open_section(typo, "input.yaml", "planner", false), ConfigError);
}

using cover::test::ScopedEnv;

// The state directory follows the XDG Base Directory specification, never the working
// directory (issue 31: cover_tasks.db in a repository's root).
TEST(StateDir, XdgStateHomeThenHomeNeverTheWorkingFolder) {
  {
    ScopedEnv xdg("XDG_STATE_HOME", "/srv/state");
    ScopedEnv home("HOME", "/home/pilot");
    EXPECT_EQ(cover::config::default_state_dir(), "/srv/state/cover");
  }
  {
    ScopedEnv xdg("XDG_STATE_HOME", nullptr);
    ScopedEnv home("HOME", "/home/pilot");
    EXPECT_EQ(cover::config::default_state_dir(), "/home/pilot/.local/state/cover");
  }
  {
    ScopedEnv xdg("XDG_STATE_HOME", "relative/state");  // ignored, as the specification asks
    ScopedEnv home("HOME", "/home/pilot");
    EXPECT_EQ(cover::config::default_state_dir(), "/home/pilot/.local/state/cover");
  }
  {
    ScopedEnv xdg("XDG_STATE_HOME", "");
    ScopedEnv home("HOME", nullptr);
    EXPECT_THROW(cover::config::default_state_dir(), cover::config::ConfigError);
  }
}

TEST(StateDir, CreatedPrivateWhenMissing) {
  const std::string dir = cover::test::scratch_path("state/cover");
  cover::config::create_state_dir(dir);
  ASSERT_TRUE(std::filesystem::is_directory(dir));
  EXPECT_EQ(std::filesystem::status(dir).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_all);
  EXPECT_NO_THROW(cover::config::create_state_dir(dir));  // already there
  std::ofstream(cover::test::scratch_path("file")) << "x";
  EXPECT_THROW(cover::config::create_state_dir(cover::test::scratch_path("file/cover")),
               cover::config::ConfigError);
}
