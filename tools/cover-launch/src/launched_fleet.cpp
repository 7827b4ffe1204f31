#include "cover/launch/launched_fleet.hpp"

#include <algorithm>
#include <filesystem>

namespace cover::launch {
namespace {

enum class VehicleKind { None, Uav, Ugv };

VehicleKind vehicle_of(const ProcessSpec& process) {
  const std::string name = std::filesystem::path(process.executable).filename().string();
  if (name == "cover-uav-agent" || name == "cover-fc-bridge") return VehicleKind::Uav;
  if (name == "cover-ugv-agent") return VehicleKind::Ugv;
  return VehicleKind::None;
}

// The process's `--id N` / `--id=N`, when N is a number written in the file.
std::optional<std::uint32_t> literal_id(const ProcessSpec& process) {
  std::string text;
  for (std::size_t i = 0; i < process.args.size(); ++i) {
    const std::string& arg = process.args[i];
    if (arg == "--id" && i + 1 < process.args.size()) text = process.args[i + 1];
    if (arg.rfind("--id=", 0) == 0) text = arg.substr(5);
  }
  if (text.empty() || text.size() > 3 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return static_cast<std::uint32_t>(std::stoul(text));
}

}  // namespace

std::optional<LaunchedFleet> launched_fleet(const LaunchFile& file) {
  if (file.kind == LaunchKind::Field) return std::nullopt;
  LaunchedFleet fleet;
  for (const auto& process : file.processes) {
    const VehicleKind kind = vehicle_of(process);
    if (kind == VehicleKind::None) continue;
    const auto id = literal_id(process);
    if (!id) return std::nullopt;
    auto& count = kind == VehicleKind::Uav ? fleet.uavs : fleet.ugvs;
    count = std::max(count, *id + 1);
  }
  if (fleet.uavs == 0 || fleet.ugvs == 0) return std::nullopt;
  return fleet;
}

std::vector<std::string> fleet_args(const std::optional<LaunchedFleet>& fleet) {
  if (!fleet) return {};
  return {"--uavs", std::to_string(fleet->uavs), "--ugvs", std::to_string(fleet->ugvs)};
}

}  // namespace cover::launch
