// config/settings_flags.hpp: a YAML file's section, the command line's flags over its keys,
// every bound checked once, errors naming the flag or the key.
#include "cover/config/settings_flags.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cover/test/scratch_dir.hpp"

namespace cover::config {
namespace {

struct Served {
  std::string bind = "127.0.0.1";
  int port = 8080;
  double rate_hz = 10.0;
  bool verbose = false;
  std::string mode = "fast";
  int retries = 3;  // in the file, never a flag

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    visit("bind", self.bind, Field("", "address to listen on"));
    visit("port", self.port, Field("", "TCP port").at_least(0.0).at_most(65535.0));
    visit("rate_hz", self.rate_hz, Field("Hz", "rate").above(0.0).at_most(50.0));
    visit("verbose", self.verbose, Field("", "log more"));
    visit("mode", self.mode, Field("", "how").one_of({"fast", "slow"}));
    visit("retries", self.retries, Field("", "tries").at_least(0.0));
  }
  void validate() const { check_fields(*this, "served"); }
};

std::string write_file(const std::string& name, const std::string& yaml) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path) << yaml;
  return path;
}

// Parses `args` (after the program's name) with the settings' flags, then loads them.
Served load(SettingsFlags<Served>& settings, std::vector<std::string> args) {
  CLI::App app;
  settings.add_to(app, {"bind", "port", "rate_hz", "verbose", "mode"});
  std::vector<const char*> argv{"program"};
  for (const auto& arg : args) argv.push_back(arg.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return settings.load();
}

std::string error_of(const std::string& file, std::vector<std::string> args) {
  SettingsFlags<Served> settings("served", file);
  try {
    load(settings, std::move(args));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* const kFile = "served: {bind: 0.0.0.0, port: 9000, rate_hz: 20, retries: 5}\n";

TEST(SettingsFlags, FileAloneGivesItsValuesAndTheDefaultsForTheRest) {
  SettingsFlags<Served> settings("served", write_file("file.yaml", kFile));
  const Served s = load(settings, {});
  EXPECT_EQ(s.bind, "0.0.0.0");
  EXPECT_EQ(s.port, 9000);
  EXPECT_DOUBLE_EQ(s.rate_hz, 20.0);
  EXPECT_EQ(s.retries, 5);
  EXPECT_FALSE(s.verbose);
  EXPECT_EQ(s.mode, "fast");
  EXPECT_EQ(settings.source(), settings.file());
}

TEST(SettingsFlags, AFlagGivenOverridesItsKeyOnly) {
  SettingsFlags<Served> settings("served", test::scratch_path("unused.yaml"));
  const std::string file = write_file("over.yaml", kFile);
  const Served s = load(settings, {"--config", file, "--port", "0", "--rate-hz", "2.5", "--verbose",
                                   "yes", "--mode", "slow"});
  EXPECT_EQ(s.port, 0);
  EXPECT_DOUBLE_EQ(s.rate_hz, 2.5);
  EXPECT_TRUE(s.verbose);
  EXPECT_EQ(s.mode, "slow");
  EXPECT_EQ(s.bind, "0.0.0.0");  // the file's: no --bind
  EXPECT_EQ(s.retries, 5);
  EXPECT_EQ(settings.source(), file + " with --mode slow --port 0 --rate-hz 2.5 --verbose yes");
}

TEST(SettingsFlags, AFileValueAFlagReplacesIsNotChecked) {
  const std::string file = write_file("replaced.yaml", "served: {port: 70000}\n");
  SettingsFlags<Served> settings("served", file);
  EXPECT_EQ(load(settings, {"--port", "81"}).port, 81);
  EXPECT_NE(error_of(file, {}).find("served.port: must be in [0, 65535]"), std::string::npos)
      << error_of(file, {});
}

TEST(SettingsFlags, ABadFlagValueNamesTheFlagAndItsKey) {
  const std::string file = write_file("bad_flag.yaml", kFile);
  // (flag, its value, the error): a wrong type, a bound, a word.
  const std::vector<std::vector<std::string>> cases = {
      {"--port", "abc", "--port abc (served.port): expected a whole number"},
      {"--port", "8080.5", "--port 8080.5 (served.port): expected a whole number"},
      {"--rate-hz", "fast", "--rate-hz fast (served.rate_hz): expected a number"},
      {"--verbose", "2", "--verbose 2 (served.verbose): expected true or false"},
      {"--port", "70000", "--port 70000 (served.port): must be in [0, 65535]"},
      {"--rate-hz", "0", "--rate-hz 0 (served.rate_hz): must be in (0, 50] Hz"},
      {"--mode", "medium", "--mode medium (served.mode): 'medium' is not one of fast, slow"}};
  for (const auto& c : cases) EXPECT_EQ(error_of(file, {c[0], c[1]}), c[2]);
}

TEST(SettingsFlags, AnUnknownOrBadKeyInTheFileNamesTheKey) {
  const std::string typo = write_file("typo.yaml", "served: {prot: 81}\n");
  const std::string error = error_of(typo, {"--port", "81"});
  EXPECT_NE(error.find("prot"), std::string::npos) << error;
  EXPECT_NE(error.find("typo.yaml"), std::string::npos) << error;
  const std::string bad = write_file("bad_key.yaml", "served: {retries: -1}\n");
  EXPECT_EQ(error_of(bad, {"--port", "81"}), "served.retries: must be >= 0");
}

TEST(SettingsFlags, AFlagForNoFieldIsAProgrammingError) {
  SettingsFlags<Served> settings("served", "unused.yaml");
  CLI::App app;
  EXPECT_THROW(settings.add_to(app, {"port", "prot"}), std::logic_error);
}

TEST(SettingsFlags, FlagsAreTheKeysWithDashesAndTheirHelpNamesTheKey) {
  SettingsFlags<Served> settings("served", "unused.yaml");
  CLI::App app;
  settings.add_to(app, {"rate_hz"});
  const CLI::Option* flag = app.get_option("--rate-hz");
  ASSERT_NE(flag, nullptr);
  EXPECT_NE(flag->get_description().find("(served.rate_hz)"), std::string::npos)
      << flag->get_description();
  EXPECT_NE(flag->get_description().find("Hz"), std::string::npos) << flag->get_description();
  EXPECT_EQ(app.get_option_no_throw("--port"), nullptr);
  EXPECT_NE(app.get_option_no_throw("--config"), nullptr);
}

}  // namespace
}  // namespace cover::config
