// cover-params: the reference of every parameter file, from the parameter structs' own
// declarations (docs/parameters.md is its output; a test keeps the two equal).
//   cover-params --markdown > docs/parameters.md
//   cover-params --check docs/parameters.md
#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "cover/startup/startup.hpp"
#include "params_reference.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 printed, or --check found the file equal; 1 --check found it different "
    "or unreadable (the difference and the command that regenerates it on stderr); 2 usage "
    "error.";

// --check: 0 when `path` holds exactly what --markdown prints.
int check(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "cover-params: cannot read " << path << "\n";
    return 1;
  }
  std::ostringstream text;
  text << in.rdbuf();
  const std::string report =
      cover::params_reference::drift_report(text.str(), cover::params_reference::markdown());
  if (report.empty()) return 0;
  std::cerr << report;
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  bool markdown = false;
  std::string check_path;
  cover::startup::Program program;
  program.name = "cover-params";
  program.description =
      "cover-params: the Markdown reference of every parameter file (docs/parameters.md): per "
      "YAML file or section, each key's unit, default, valid values and meaning, printed "
      "from the same declarations that load and validate them";
  program.exit_codes = kExitCodes;
  program.shutdown_signals = false;  // prints and ends
  program.add_flags = [&](CLI::App& app) {
    auto* print = app.add_flag("--markdown", markdown, "print the reference to stdout");
    app.add_option("--check", check_path,
                   "compare FILE with the reference; exit 1 with the difference when they differ")
        ->type_name("FILE")
        ->excludes(print);
  };
  program.check_flags = [&](const CLI::App&) {
    if (!markdown && check_path.empty()) throw CLI::RequiredError("--markdown or --check FILE");
  };
  return cover::startup::run_main(argc, argv, program, [&](const CLI::App&) {
    if (!check_path.empty()) return check(check_path);
    std::cout << cover::params_reference::markdown();
    return std::cout.good() ? 0 : 1;
  });
}
