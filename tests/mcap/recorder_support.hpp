#pragma once

#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cover/msg/types.hpp"
#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

// What the recorder tests share: running `cover` and the node readers, and a sample as the
// independent decoder prints it.
namespace cover::test {

inline std::string find_node() {
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "";
  for (std::size_t at = 0; at <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', at), dirs.size());
    const auto candidate = std::filesystem::path(dirs.substr(at, end - at)) / "node";
    if (!dirs.substr(at, end - at).empty() && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
    at = end + 1;
  }
  return "";
}

struct Output {
  int code = -1;
  std::vector<std::string> lines;  // stdout
};

// Runs a program to its end (stdout captured, stderr into `log` in the scratch folder).
inline Output run(const std::vector<std::string>& argv, const std::string& log,
                  std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
  process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = scratch_path(log);
  process::ChildProcess child(argv, options);
  Output out;
  while (const auto line = child.read_line(scaled(timeout))) out.lines.push_back(*line);
  out.code = child.wait(scaled(timeout)).value_or(-1);
  return out;
}

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};

// A sample as @foxglove/omgidl-serialization decodes it and read_mcap.js prints it: enums
// as their numeric value, 64-bit integers as decimal strings (beyond 2^53), doubles as
// numbers.
template <typename T>
nlohmann::json decoded_form(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<std::uint32_t>(value);
  } else if constexpr (std::is_same_v<T, std::int64_t> || std::is_same_v<T, std::uint64_t>) {
    return std::to_string(value);
  } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
    return value;
  } else if constexpr (IsVector<T>::value) {
    nlohmann::json array = nlohmann::json::array();
    for (const auto& element : value) array.push_back(decoded_form(element));
    return array;
  } else {
    nlohmann::json object = nlohmann::json::object();
    msg::visit_fields(
        value, [&](const char* name, const auto& field) { object[name] = decoded_form(field); });
    return object;
  }
}

}  // namespace cover::test
