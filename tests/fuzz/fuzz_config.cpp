// Every config loader (config/*.yaml and the files they name). Two modes, by the first byte:
//  - raw: the rest of the input is the file. Contract: the loader returns, or throws
//    ConfigError (DdsError for dds.yaml) with a message; never another exception.
//  - hostile value: one scalar of the shipped file is replaced by NaN, an infinity, a huge
//    or negative number, an empty string, a list or a map. Contract as above, and a NaN or
//    infinity put where the shipped file has a number is always refused: no parameter is
//    meaningfully NaN, and an infinite one is a unit mistake.
// Inputs are parsed from memory through each loader's from_yaml (the path its load_file
// takes is only the virtual source): no file per input, so nothing to clean up or wait on.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
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
#include "uav_agent_params.hpp"
#include "ugv_agent_params.hpp"

namespace {

namespace fs = std::filesystem;
using cover::fuzz::require;
using cover::fuzz::violated;

struct Loader {
  const char* name;
  const char* shipped;  // relative to config/
  // Loads a parsed document as if read from `path` (beside the shipped file, so relative
  // paths inside it, `task_file: ../tasks/scenario2.yaml`, resolve as from config/).
  std::function<void(const YAML::Node& document, const std::string& path)> load;
};

const std::vector<Loader>& loaders() {
  using Doc = const YAML::Node&;
  using Path = const std::string&;
  static const std::vector<Loader> all = {
      {"sampc", "sampc.yaml", [](Doc d, Path p) { cover::sampc::SampcParams::from_yaml(d, p); }},
      {"planner", "planner.yaml",
       [](Doc d, Path p) { cover::planner::PlannerParams::from_yaml(d, p); }},
      {"mission", "mission.yaml",
       [](Doc d, Path p) { cover::mission::MissionParams::from_yaml(d, p); }},
      {"dds", "dds.yaml",
       [](Doc d, Path p) {
         cover::dds::ParticipantOptions::from_yaml(d, p);
         cover::dds::ParticipantOptions::from_yaml(d, p, "wifi");
       }},
      {"task_manager", "task_manager.yaml",
       [](Doc d, Path p) { cover::task_manager::TaskLimits::from_yaml(d, p); }},
      {"ugv_agent", "ugv_agent.yaml",
       [](Doc d, Path p) { cover::ugv::UgvAgentParams::from_yaml(d, p); }},
      {"world", "sim/world_default.yaml",
       [](Doc d, Path p) { cover::sim::WorldParams::from_yaml(d, p); }},
      {"sim_process", "sim/sim_process.yaml",
       [](Doc d, Path p) { cover::sim::SimProcessParams::from_yaml(d, p); }},
      {"scenario", "scenarios/scenario2.yaml",
       [](Doc d, Path p) { cover::sim::Scenario::from_yaml(d, p); }},
      {"launch", "launch/example.yaml",
       [](Doc d, Path p) { cover::launch::LaunchFile::parse(d, p, fs::path(p).parent_path()); }},
      {"intake", "intake.yaml", [](Doc d, Path p) { cover::wire::IntakeLimits::from_yaml(d, p); }},
      {"uav_agent", "uav_agent.yaml",
       [](Doc d, Path p) { cover::uav_agent::UavAgentParams::from_yaml(d, p); }},
  };
  return all;
}

// Where the input is said to come from: no file is written, nothing is left behind.
std::string input_path(const Loader& loader) {
  return (fs::path(COVER_CONFIG_DIR) / loader.shipped).parent_path() / "fuzz-input.yaml";
}

// Returns true when the loader accepted the document; a wrong kind of exception violates.
// `text` is the document as a file would hold it: parsed here unless `document` is given.
bool accepted(const Loader& loader, const std::string& text, const YAML::Node* document) {
  const std::string path = input_path(loader);
  try {
    loader.load(document ? *document : cover::config::parse_yaml(text, path), path);
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
  const bool ok = accepted(loader, "", &root);
  if (was_number && pick <= 2 && ok) {
    YAML::Emitter out;
    out << root;
    violated(std::string(loader.name) + ": accepted " + values[pick] + " in\n" + out.c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cover::fuzz::FuzzInput in(data, size);
  const Loader& loader = loaders()[in.byte() % loaders().size()];
  if (in.byte() % 2 == 0) {
    accepted(loader, in.rest(), nullptr);
  } else {
    hostile_value(loader, in);
  }
  return 0;
}
