#include "record_commands.hpp"

#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iostream>

#include "cover/logging/log.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/recording/bag_info.hpp"

namespace cover::cli {
namespace {

// ros2 bag's default name, as one file: cover_YYYY_MM_DD-HH_MM_SS.mcap in the working
// directory.
std::string default_file_name() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "cover_%Y_%m_%d-%H_%M_%S.mcap", &local);
  return name;
}

// Room for ~0.5 s of a 4-UAV, 8-UGV fleet's samples while the recorder is descheduled:
// with the OS default (208 KiB) a lockstep run under load lost 50-100 ms windows.
constexpr int kRecorderReceiveBufferBytes = 8 * 1024 * 1024;

constexpr int kStopQuietMs = 200;
constexpr int kStopDrainMaxMs = 2000;  // within cover-launch's default grace period (3 s)

std::string compression_label(const mcap::Compression compression) {
  const auto name = mcap::compression_name(compression);
  return name.empty() ? "none" : std::string(name);
}

}  // namespace

RecordCommands::RecordCommands(CLI::App& app) {
  record_ = app.add_subcommand(
      "record",
      "Record DDS samples into an MCAP file (CDR as on the wire, omgidl schemas): every "
      "catalogued topic of the fleet by default, each subscribed when its first writer appears; "
      "SIGINT stops and closes the file");
  record_->add_option("-o,--output", record_options_.path,
                      "the MCAP file (default: cover_YYYY_MM_DD-HH_MM_SS.mcap here)");
  record_->add_option("--topics", record_options_.topic_globs,
                      "record only topics matching these globs, e.g. 'cover/uav/*' "
                      "(default: all)");
  record_->add_option("--compression", compression_, "chunk compression")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}))
      ->capture_default_str();
  record_->add_option("--duration", duration_s_, "stop after S seconds (default: at SIGINT)");
  record_
      ->add_option("--chunk-duration", chunk_duration_s_,
                   "seconds of samples per chunk: what a killed recorder can lose")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
  record_->add_option("--uavs", record_options_.fleet.uavs, "UAV ids 0..N-1 to bind topics for")
      ->capture_default_str();
  record_->add_option("--ugvs", record_options_.fleet.ugvs, "UGV ids 0..N-1 to bind topics for")
      ->capture_default_str();
  record_dds_.add_to(*record_);
  record_->footer(
      "Exit: 0 recorded and closed, 2 usage or the file cannot be created, 3 the file could\n"
      "not be written (disk full...). A SIGKILLed recorder loses at most --chunk-duration.");

  auto* bag = app.add_subcommand("bag", "Inspect MCAP recordings");
  bag->require_subcommand(1);
  info_ = bag->add_subcommand("info", "Topics, types, counts, rates, duration, compression");
  info_->add_option("file", bag_path_, "an MCAP file")->required();
  info_->add_flag("--json", json_, "one JSON object");
  info_->footer(
      "Exit: 0 complete file, 1 cut or damaged (what is readable is reported, each problem\n"
      "with its byte offset), 2 not an MCAP file or unreadable.");

  play_ = app.add_subcommand(
      "play", "Publish a recording's samples again with their original timing (or scaled)");
  play_->add_option("file", play_options_.path, "an MCAP file made by cover record")->required();
  play_->add_option("--rate", play_options_.rate, "speed factor (2: twice as fast)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  play_->add_option("--topics", play_options_.topic_globs,
                    "play only topics matching these globs (default: all)");
  play_->add_option("--start", play_options_.start_s, "skip the first S seconds")
      ->check(CLI::NonNegativeNumber);
  play_
      ->add_option("--delay", play_options_.delay_s,
                   "seconds between making the writers and the first sample (discovery)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  play_->add_flag("--lockstep", play_options_.lockstep,
                  "replay a lockstep run into live UAV agents by the simulator's protocol: per "
                  "tick the inputs it names, the tick, then each agent's answer awaited (as fast "
                  "as they answer); recorded commands are not played (docs/recording.md)");
  play_dds_.add_to(*play_);
  play_->footer(
      "Exit: 0 played to the end (or stopped by SIGINT), 1 the file is cut or damaged (its\n"
      "readable part played; problems printed with their byte offsets), 2 usage or not an\n"
      "MCAP file.");
}

bool RecordCommands::chosen() const {
  return record_->parsed() || info_->parsed() || play_->parsed();
}

int RecordCommands::run() {
  if (record_->parsed()) return record();
  if (info_->parsed()) return info();
  return play();
}

int RecordCommands::record() {
  if (record_options_.path.empty()) record_options_.path = default_file_name();
  record_options_.writer.compression = *mcap::parse_compression(compression_);
  record_options_.writer.chunk_duration_ns = static_cast<std::int64_t>(chunk_duration_s_ * 1e9);
  dds::ParticipantOptions participant_options = record_dds_.resolve("cover-recorder");
  participant_options.receive_buffer_bytes = kRecorderReceiveBufferBytes;
  dds::Participant participant(participant_options);
  std::unique_ptr<recording::Recorder> recorder;
  try {
    recorder = std::make_unique<recording::Recorder>(participant, record_options_);
  } catch (const std::runtime_error& e) {
    std::cerr << "cover record: " << e.what() << "\n";
    return kBagUsage;
  }
  spdlog::info(
      "recording into {} ({} chunks of at most {} s){}: each catalogued topic of {} UAV(s) and "
      "{} UGV(s){} as its first writer appears",
      record_options_.path, compression_label(record_options_.writer.compression),
      chunk_duration_s_, duration_s_ > 0 ? fmt::format(" for {:.1f} s", duration_s_) : "",
      record_options_.fleet.uavs, record_options_.fleet.ugvs,
      record_options_.topic_globs.empty()
          ? ""
          : fmt::format(" matching {}", fmt::join(record_options_.topic_globs, " ")));
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  bool ok = true;
  while (ok && !process::ShutdownSignal::requested() &&
         (duration_s_ <= 0 || elapsed_s() < duration_s_)) {
    ok = recorder->pump(50);
  }
  // A stop (SIGINT, --duration) may come while the receive path is still behind: what
  // the network buffered is written before the file is closed.
  ok = ok && recorder->drain(kStopQuietMs, kStopDrainMaxMs);
  ok = recorder->close() && ok;
  const recording::RecorderStats stats = recorder->stats();
  if (!ok) {
    spdlog::error("cannot write {}: {}", record_options_.path, recorder->error());
    return kBagWriteFailed;
  }
  spdlog::info("recorded {} samples of {} topics ({} subscribed) into {} ({} bytes), {} dropped",
               stats.written, stats.topics_heard, stats.topics_subscribed, record_options_.path,
               stats.bytes_written, stats.dropped);
  // What the recorder cost, for cover-bench record's share of a core during a run.
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  spdlog::info("recorder CPU {:.3f} s over {:.3f} s: {:.1f} % of one core", cpu_s, elapsed_s(),
               100.0 * cpu_s / std::max(elapsed_s(), 1e-9));
  return kBagOk;
}

int RecordCommands::info() const {
  const recording::BagSummary summary = recording::summarize_bag(bag_path_);
  if (json_) {
    std::cout << recording::bag_summary_json(summary).dump() << std::endl;
  } else {
    std::cout << recording::format_bag_summary(summary);
  }
  if (!summary.is_mcap) return kBagUsage;
  return summary.issues.empty() ? kBagOk : kBagDamaged;
}

int RecordCommands::play() {
  dds::Participant participant(play_dds_.resolve("cover-player"));
  recording::Player player(participant, play_options_);
  spdlog::info(
      "playing {} at {}x{}", play_options_.path, play_options_.rate,
      play_options_.start_s > 0 ? fmt::format(" from {:.1f} s", play_options_.start_s) : "");
  const recording::PlayStats stats =
      player.run([] { return process::ShutdownSignal::requested(); });
  for (const auto& topic : stats.skipped_topics) {
    spdlog::warn("not played: {} (not a catalogued topic of its recorded type)", topic);
  }
  for (const auto& issue : stats.issues) {
    std::cerr << "cover play: " << play_options_.path << ": at byte " << issue.offset << ": "
              << issue.what << "\n";
  }
  if (!stats.is_mcap) return kBagUsage;
  spdlog::info("published {} samples{}{}", stats.published,
               stats.undecodable ? ", " + std::to_string(stats.undecodable) + " undecodable" : "",
               stats.stopped ? " (stopped)" : "");
  if (play_options_.lockstep) {
    spdlog::info("lockstep: {} agent answers awaited, {} not heard within {} s",
                 stats.answers_awaited, stats.answers_missing, play_options_.answer_timeout_s);
  }
  return stats.issues.empty() ? kBagOk : kBagDamaged;
}

}  // namespace cover::cli
