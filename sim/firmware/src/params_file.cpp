#include "cover/firmware/params_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cover::firmware {

FirmwareParams read_params_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read firmware parameters " + path.string());
  FirmwareParams params;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& c : line) {
      if (c == ',' || c == '\t') c = ' ';  // ArduPilot's .parm also writes NAME,VALUE
    }
    std::istringstream words(line);
    std::string name;
    std::string value;
    std::string extra;
    if (!(words >> name)) continue;
    if (!(words >> value) || (words >> extra)) {
      throw std::runtime_error(path.string() + ":" + std::to_string(number) +
                               ": expected `NAME value`");
    }
    params.emplace_back(name, value);
  }
  return params;
}

void write_arducopter_params(const std::filesystem::path& path, const FirmwareParams& params,
                             int own_system_id) {
  std::ofstream out(path);
  for (const auto& [name, value] : params) {
    out << name << " " << (value == kOwnSystemId ? std::to_string(own_system_id) : value) << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace cover::firmware
