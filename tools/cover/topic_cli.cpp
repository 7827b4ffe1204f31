#include "topic_cli.hpp"

#include <CLI/CLI.hpp>

namespace cover::cli {

TopicCli::TopicCli(CLI::App& app) {
  topics_ = app.add_subcommand("topics", "List the topic catalogue");
  auto* json_flag = topics_->add_flag("--json", topics_json_, "JSON lines instead of a table");
  topics_->add_flag("--markdown", topics_markdown_, "The table of docs/topics.md")
      ->excludes(json_flag);

  echo_ = app.add_subcommand("echo", "Print samples of a topic as they arrive");
  echo_->add_option("topic", echo_request_.topic, "e.g. cover/ugv/0/imu")->required();
  echo_->add_option("--count", echo_request_.count, "Stop after N samples (default: never)");
  echo_->add_option("--timeout", echo_request_.timeout_s,
                    "Give up after S seconds without all samples");
  echo_->add_flag("--json", echo_request_.json, "One compact JSON object per line");
  echo_dds_.add_to(*echo_);

  pub_ = app.add_subcommand("pub", "Publish a sample given as JSON");
  pub_->add_option("topic", pub_request_.topic, "e.g. cover/uav/0/cmd")->required();
  pub_->add_option("json", pub_request_.json, "Sample as JSON; missing fields are zero")
      ->required();
  pub_->add_option("--rate", pub_request_.rate_hz, "Publish at HZ (default: once)");
  pub_->add_option("--count", pub_request_.count, "Number of samples (default 1)");
  pub_->add_option("--wait", pub_request_.wait_for_reader_s,
                   "Seconds to wait for a subscriber before publishing")
      ->capture_default_str();
  pub_dds_.add_to(*pub_);
  pub_->footer(pub_help_footer());
}

bool TopicCli::chosen() const {
  return topics_->parsed() || echo_->parsed() || pub_->parsed();
}

int TopicCli::run() {
  if (topics_->parsed()) {
    return list_topics(topics_json_       ? TopicsFormat::Json
                       : topics_markdown_ ? TopicsFormat::Markdown
                                          : TopicsFormat::Table);
  }
  if (echo_->parsed()) return echo(echo_dds_.resolve("cover-echo"), echo_request_);
  return publish(pub_dds_.resolve("cover-pub"), pub_request_);
}

}  // namespace cover::cli
