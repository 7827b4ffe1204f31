// cover: COVER's ground-station command line.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cover/dds/cli_options.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "topic_commands.hpp"

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  CLI::App app{"cover: ground station for COVER cross-vehicle missions"};
  app.require_subcommand(1);

  bool topics_json = false;
  bool topics_markdown = false;
  auto* topics = app.add_subcommand("topics", "List the topic catalogue");
  auto* json_flag = topics->add_flag("--json", topics_json, "JSON lines instead of a table");
  topics->add_flag("--markdown", topics_markdown, "The table of docs/topics.md")
      ->excludes(json_flag);

  cover::cli::EchoRequest echo_request;
  cover::dds::DdsCliOptions echo_dds;
  auto* echo = app.add_subcommand("echo", "Print samples of a topic as they arrive");
  echo->add_option("topic", echo_request.topic, "e.g. cover/ugv/0/imu")->required();
  echo->add_option("--count", echo_request.count, "Stop after N samples (default: never)");
  echo->add_option("--timeout", echo_request.timeout_s,
                   "Give up after S seconds without all samples");
  echo->add_flag("--json", echo_request.json, "One compact JSON object per line");
  echo_dds.add_to(*echo);

  cover::cli::PubRequest pub_request;
  cover::dds::DdsCliOptions pub_dds;
  auto* pub = app.add_subcommand("pub", "Publish a sample given as JSON");
  pub->add_option("topic", pub_request.topic, "e.g. cover/uav/0/cmd")->required();
  pub->add_option("json", pub_request.json, "Sample as JSON; missing fields are zero")->required();
  pub->add_option("--rate", pub_request.rate_hz, "Publish at HZ (default: once)");
  pub->add_option("--count", pub_request.count, "Number of samples (default 1)");
  pub->add_option("--wait", pub_request.wait_for_reader_s,
                  "Seconds to wait for a subscriber before publishing")
      ->capture_default_str();
  pub_dds.add_to(*pub);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*topics) {
      using cover::cli::TopicsFormat;
      return cover::cli::list_topics(topics_json       ? TopicsFormat::Json
                                     : topics_markdown ? TopicsFormat::Markdown
                                                       : TopicsFormat::Table);
    }
    if (*echo) return cover::cli::echo(echo_dds.resolve("cover-echo"), echo_request);
    if (*pub) return cover::cli::publish(pub_dds.resolve("cover-pub"), pub_request);
  } catch (const std::exception& e) {
    std::cerr << "cover: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
