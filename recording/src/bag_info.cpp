#include "cover/recording/bag_info.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <ctime>

namespace cover::recording {
namespace {

std::string human_bytes(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 3) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

std::string wall_time(std::uint64_t ns) {
  const std::time_t seconds = static_cast<std::time_t>(ns / 1'000'000'000ULL);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char date[40];
  std::strftime(date, sizeof date, "%b %e %Y %H:%M:%S", &utc);
  char text[96];
  std::snprintf(text, sizeof text, "%s.%03u UTC (%" PRIu64 ".%09" PRIu64 ")", date,
                static_cast<unsigned>((ns / 1'000'000ULL) % 1000),
                static_cast<std::uint64_t>(ns / 1'000'000'000U),
                static_cast<std::uint64_t>(ns % 1'000'000'000U));
  return text;
}

double seconds_between(std::uint64_t first_ns, std::uint64_t last_ns) {
  return last_ns > first_ns ? static_cast<double>(last_ns - first_ns) * 1e-9 : 0.0;
}

}  // namespace

BagSummary summarize_bag(const std::string& path) {
  BagSummary summary;
  summary.path = path;
  mcap::Reader reader(path);
  std::map<std::uint16_t, BagTopic> topics;
  reader.scan([&](const mcap::MessageView& m) {
    BagTopic& topic = topics[m.channel->id];
    const std::uint64_t t = m.header.log_time_ns;
    if (topic.count == 0) {
      topic.topic = m.channel->topic;
      topic.type = m.schema != nullptr ? m.schema->name : "";
      topic.encoding = m.channel->message_encoding;
      topic.first_log_ns = topic.last_log_ns = t;
    }
    ++topic.count;
    topic.first_log_ns = std::min(topic.first_log_ns, t);
    topic.last_log_ns = std::max(topic.last_log_ns, t);
    if (summary.message_count == 0) summary.start_ns = summary.end_ns = t;
    ++summary.message_count;
    summary.start_ns = std::min(summary.start_ns, t);
    summary.end_ns = std::max(summary.end_ns, t);
    return true;
  });
  summary.size_bytes = reader.file_size();
  summary.issues = reader.issues();
  summary.is_mcap = reader.is_mcap();
  summary.finished = reader.finished();
  summary.library = reader.library();
  for (const auto& chunk : reader.chunks()) {
    ++summary.chunks_by_compression[chunk.compression.empty() ? "none" : chunk.compression];
    summary.compressed_bytes += chunk.compressed_size;
    summary.uncompressed_bytes += chunk.uncompressed_size;
  }
  for (auto& [id, topic] : topics) {
    const double span_s = seconds_between(topic.first_log_ns, topic.last_log_ns);
    topic.rate_hz = topic.count > 1 && span_s > 0 ? (topic.count - 1) / span_s : 0.0;
    summary.topics.push_back(topic);
  }
  std::sort(summary.topics.begin(), summary.topics.end(),
            [](const BagTopic& a, const BagTopic& b) { return a.topic < b.topic; });
  return summary;
}

std::string format_bag_summary(const BagSummary& s) {
  std::string out;
  char line[512];
  auto add = [&](const char* label, const std::string& value) {
    std::snprintf(line, sizeof line, "%-19s%s\n", label, value.c_str());
    out += line;
  };
  add("Files:", s.path);
  add("Bag size:", human_bytes(s.size_bytes));
  add("Storage id:", "mcap");
  if (s.is_mcap) {
    add("Closed:", s.finished ? "yes (summary and footer)"
                              : "NO: read by scanning (recorder killed, or file cut)");
    std::snprintf(line, sizeof line, "%.3fs", seconds_between(s.start_ns, s.end_ns));
    add("Duration:", line);
    if (s.message_count > 0) {
      add("Start:", wall_time(s.start_ns));
      add("End:", wall_time(s.end_ns));
    }
    add("Messages:", std::to_string(s.message_count));
    std::string compression;
    for (const auto& [name, count] : s.chunks_by_compression) {
      compression +=
          (compression.empty() ? "" : ", ") + name + " (" + std::to_string(count) + " chunks)";
    }
    if (s.uncompressed_bytes > 0) {
      std::snprintf(line, sizeof line, ", %s -> %s", human_bytes(s.uncompressed_bytes).c_str(),
                    human_bytes(s.compressed_bytes).c_str());
      compression += line;
    }
    add("Compression:", compression.empty() ? "(no chunks)" : compression);
    bool first = true;
    for (const auto& t : s.topics) {
      std::snprintf(line, sizeof line,
                    "Topic: %s | Type: %s | Count: %" PRIu64
                    " | Rate: %.1f Hz | Serialization Format: %s",
                    t.topic.c_str(), t.type.c_str(), t.count, t.rate_hz, t.encoding.c_str());
      add(first ? "Topic information:" : "", line);
      first = false;
    }
  }
  for (const auto& issue : s.issues) {
    add("Problem:", "at byte " + std::to_string(issue.offset) + ": " + issue.what);
  }
  return out;
}

nlohmann::json bag_summary_json(const BagSummary& s) {
  nlohmann::json topics = nlohmann::json::array();
  for (const auto& t : s.topics) {
    topics.push_back({{"topic", t.topic},
                      {"type", t.type},
                      {"serialization_format", t.encoding},
                      {"count", t.count},
                      {"rate_hz", t.rate_hz},
                      {"first_log_ns", t.first_log_ns},
                      {"last_log_ns", t.last_log_ns}});
  }
  nlohmann::json issues = nlohmann::json::array();
  for (const auto& issue : s.issues)
    issues.push_back({{"offset", issue.offset}, {"what", issue.what}});
  return {{"file", s.path},
          {"size_bytes", s.size_bytes},
          {"storage", "mcap"},
          {"is_mcap", s.is_mcap},
          {"closed", s.finished},
          {"library", s.library},
          {"message_count", s.message_count},
          {"start_ns", s.start_ns},
          {"end_ns", s.end_ns},
          {"duration_s", seconds_between(s.start_ns, s.end_ns)},
          {"chunks", s.chunks_by_compression},
          {"compressed_bytes", s.compressed_bytes},
          {"uncompressed_bytes", s.uncompressed_bytes},
          {"topics", topics},
          {"issues", issues}};
}

}  // namespace cover::recording
