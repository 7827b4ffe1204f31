#pragma once

#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

// A benchmark that measured nothing says why and fails. Every subcommand prints what it
// did measure, a figure it did not as null (JSON) or "not measured" (text), never as 0;
// then, when a figure it was asked for is missing, it names each one on stderr and exits
// kExitNotMeasured, so that a script or a reader cannot take an empty run for a result.
namespace cover::bench {

// Exit codes shared by the subcommands: 0 measured; 1 a run failed (a mission, a check the
// benchmark makes); 2 usage; 3 `scenario`'s mission failed; 4 something asked for was not
// measured (kExitNotMeasured).
inline constexpr int kExitNotMeasured = 4;

// What a run did not measure, each with why.
class NotMeasured {
 public:
  void add(std::string what_and_why) { reasons_.push_back(std::move(what_and_why)); }
  bool empty() const { return reasons_.empty(); }
  const std::vector<std::string>& reasons() const { return reasons_; }

  // `code` when everything was measured; otherwise prints "cover-bench BENCH: not measured:
  // REASON" per reason on stderr and returns `code` if it already reports a failure, else
  // kExitNotMeasured.
  int exit_code(const std::string& bench, int code = 0) const {
    for (const std::string& reason : reasons_) {
      std::cerr << "cover-bench " << bench << ": not measured: " << reason << "\n";
    }
    if (reasons_.empty() || code != 0) return code;
    return kExitNotMeasured;
  }

 private:
  std::vector<std::string> reasons_;
};

// A measured figure as JSON: null when it was not measured (NaN or infinite).
inline nlohmann::json figure_json(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// A figure for a readable table, printf-formatted, or "not measured".
inline std::string figure_text(const char* format, double value) {
  if (!std::isfinite(value)) return "not measured";
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace cover::bench
