// Every config loader (config/*.yaml and the files they name). Two modes, by the first byte:
//  - raw: the rest of the input is the file. Contract: the loader returns, or throws
//    ConfigError (DdsError for dds.yaml) with a message; never another exception.
//  - hostile value: one scalar of the shipped file is replaced by NaN, an infinity, a huge
//    or negative number, an empty string, a list or a map. Contract as above, and a NaN or
//    infinity put where the shipped file has a number is always refused: no parameter is
//    meaningfully NaN, and an infinite one is a unit mistake.
#include <yaml-cpp/yaml.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/dds/dds_error.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/launch/launch_file.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/planner/planner_params.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/sim/world_params.hpp"
#include "cover/task_manager/task_limits.hpp"
#include "cover/wire/intake.hpp"
#include "fuzz_input.hpp"
#include "sim_process_params.hpp"
#include "ugv_agent_params.hpp"

namespace {

namespace fs = std::filesystem;
using cover::fuzz::require;
using cover::fuzz::violated;

struct Loader {
  const char* name;
  const char* shipped;  // relative to config/
  std::function<void(const std::string& path)> load;
};

const std::vector<Loader>& loaders() {
  static const std::vector<Loader> all = {
      {"sampc", "sampc.yaml",
       [](const std::string& p) { cover::sampc::SampcParams::load_file(p); }},
      {"planner", "planner.yaml",
       [](const std::string& p) { cover::planner::PlannerParams::load_file(p); }},
      {"mission", "mission.yaml",
       [](const std::string& p) { cover::mission::MissionParams::load_file(p); }},
      {"dds", "dds.yaml",
       [](const std::string& p) {
         cover::dds::ParticipantOptions::load_file(p);
         cover::dds::ParticipantOptions::load_file(p, "wifi");
       }},
      {"task_manager", "task_manager.yaml",
       [](const std::string& p) { cover::task_manager::TaskLimits::load_file(p); }},
      {"ugv_agent", "ugv_agent.yaml",
       [](const std::string& p) { cover::ugv::UgvAgentParams::load_file(p); }},
      {"world", "sim/world_default.yaml",
       [](const std::string& p) { cover::sim::WorldParams::load_file(p); }},
      {"sim_process", "sim/sim_process.yaml",
       [](const std::string& p) { cover::sim::SimProcessParams::load_file(p); }},
      {"scenario", "scenarios/scenario2.yaml",
       [](const std::string& p) { cover::sim::Scenario::load_file(p); }},
      {"launch", "launch/example.yaml",
       [](const std::string& p) { cover::launch::LaunchFile::load_file(p); }},
      {"intake", "intake.yaml",
       [](const std::string& p) { cover::wire::IntakeLimits::load_file(p); }},
  };
  return all;
}

// A private folder beside the shipped ones (symlinked), so relative paths inside a file
// (`task_file: ../tasks/scenario2.yaml`) resolve as they would from config/.
const fs::path& work_dir() {
  static const fs::path dir = [] {
    const fs::path d =
        fs::temp_directory_path() / ("cover-fuzz-config-" + std::to_string(getpid()));
    fs::create_directories(d / "fuzz");
    for (const auto& entry : fs::directory_iterator(COVER_CONFIG_DIR)) {
      const fs::path link = d / entry.path().filename();
      if (!fs::exists(fs::symlink_status(link))) fs::create_symlink(entry.path(), link);
    }
    return d;
  }();
  // Registered once `dir` is made, so that it runs before dir's destructor, not after it.
  static const bool removed_at_exit = (std::atexit([] { fs::remove_all(dir); }), true);
  (void)removed_at_exit;
  return dir;
}

std::string write_input(const std::string& text) {
  const fs::path path = work_dir() / "fuzz" / "input.yaml";
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path.string();
}

// Returns true when the loader accepted the file; a wrong kind of exception violates.
bool accepted(const Loader& loader, const std::string& text) {
  const std::string path = write_input(text);
  try {
    loader.load(path);
    return true;
  } catch (const cover::config::ConfigError& e) {
    require(std::string(e.what()).size() > 0, std::string(loader.name) + ": empty error");
  } catch (const cover::dds::DdsError& e) {
    require(std::string(loader.name) == "dds" || std::string(loader.name) == "launch",
            std::string(loader.name) + ": DdsError from a non-DDS loader: " + e.what());
  } catch (const std::exception& e) {
    violated(std::string(loader.name) + ": not a ConfigError: " + e.what());
  }
  return false;
}

void collect_scalars(YAML::Node node, std::vector<YAML::Node>& out) {
  if (node.IsScalar()) {
    out.push_back(node);
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) collect_scalars(node[i], out);
  } else if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) collect_scalars(it->second, out);
  }
}

// A plain (unquoted) scalar that reads as a number: a quoted "0" is a string parameter
// (a launch file's argument), where ".nan" is just text.
bool is_number(const YAML::Node& scalar) {
  double value = 0.0;
  return scalar.Tag() != "!" && YAML::convert<double>::decode(scalar, value);
}

// The shipped file, parsed once; each input edits a deep copy.
YAML::Node shipped_copy(const Loader& loader) {
  static std::map<std::string, YAML::Node> parsed;
  auto found = parsed.find(loader.name);
  if (found == parsed.end()) {
    found = parsed
                .emplace(loader.name,
                         YAML::LoadFile(std::string(COVER_CONFIG_DIR) + "/" + loader.shipped))
                .first;
  }
  return YAML::Clone(found->second);
}

void hostile_value(const Loader& loader, cover::fuzz::FuzzInput& in) {
  YAML::Node root = shipped_copy(loader);
  std::vector<YAML::Node> scalars;
  collect_scalars(root, scalars);
  if (scalars.empty()) return;
  YAML::Node target = scalars[static_cast<std::size_t>(in.range(0, 1 << 20)) % scalars.size()];
  const bool was_number = is_number(target);
  static const std::vector<std::string> values = {".nan",
                                                  ".inf",
                                                  "-.inf",
                                                  "1e308",
                                                  "-1e308",
                                                  "-1",
                                                  "0",
                                                  "-0.0",
                                                  "4294967296",
                                                  "-2147483649",
                                                  "99999999999999999999",
                                                  "1e-320",
                                                  "",
                                                  "~",
                                                  "'x'"};
  const std::size_t pick = in.byte() % (values.size() + 2);
  if (pick < values.size()) {
    target = YAML::Load(values[pick].empty() ? "''" : values[pick]);
  } else if (pick == values.size()) {
    target = YAML::Load("[1, 2]");
  } else {
    target = YAML::Load("{a: 1}");
  }
  YAML::Emitter out;
  out << root;
  const bool ok = accepted(loader, out.c_str());
  if (was_number && pick <= 2) {
    require(!ok, std::string(loader.name) + ": accepted " + values[pick] + " in\n" + out.c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cover::fuzz::FuzzInput in(data, size);
  const Loader& loader = loaders()[in.byte() % loaders().size()];
  if (in.byte() % 2 == 0) {
    accepted(loader, in.rest());
  } else {
    hostile_value(loader, in);
  }
  return 0;
}
