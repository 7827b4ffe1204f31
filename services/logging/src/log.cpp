#include "cover/logging/log.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <cstdlib>

namespace cover::logging {

void init(const std::string& process_name, const std::string& level) {
  auto logger = spdlog::stderr_color_mt(process_name);
  logger->set_pattern("%H:%M:%S.%e %^%-5l%$ [%n] %v");
  std::string chosen = level;
  if (chosen.empty()) {
    const char* env = std::getenv("COVER_LOG_LEVEL");
    chosen = env ? env : "info";
  }
  logger->set_level(spdlog::level::from_str(chosen));
  spdlog::set_default_logger(logger);
}

void add_file(const std::string& path) {
  auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path);
  sink->set_pattern("%Y-%m-%d %H:%M:%S.%e %-5l [%n] %v");
  spdlog::default_logger()->sinks().push_back(std::move(sink));
  // Lines are rare decisions; flushing each keeps the file complete if the process is killed.
  spdlog::default_logger()->flush_on(spdlog::level::info);
}

}  // namespace cover::logging
