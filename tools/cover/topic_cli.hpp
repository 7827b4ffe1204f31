#pragma once

#include "cover/dds/cli_options.hpp"
#include "topic_commands.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// `cover topics|echo|pub`: the topic catalogue, and samples of one topic read or written
// as JSON (topic_commands.hpp).
class TopicCli {
 public:
  explicit TopicCli(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  CLI::App* topics_ = nullptr;
  CLI::App* echo_ = nullptr;
  CLI::App* pub_ = nullptr;
  bool topics_json_ = false;
  bool topics_markdown_ = false;
  EchoRequest echo_request_;
  dds::DdsCliOptions echo_dds_;
  PubRequest pub_request_;
  dds::DdsCliOptions pub_dds_;
};

}  // namespace cover::cli
