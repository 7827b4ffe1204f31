#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "cover/mavlink/link.hpp"
#include "cover/mavlink/parser.hpp"

namespace cover::fc_bridge {

// Keeps the MAVLink link to the autopilot open and reads it on a thread of its own: bytes
// through the stream parser to `on_frame`. A link that fails (a serial cable pulled, a
// device gone) is opened again every `reopen_period_s` until it is back; each loss and
// each return is logged once. `write` may be called from any thread.
class LinkKeeper {
 public:
  using FrameHandler = std::function<void(const mavlink::Frame&, const mavlink::ParserStats&)>;
  LinkKeeper(std::unique_ptr<mavlink::Link> link, mavlink::ParserOptions parser_options);
  ~LinkKeeper();

  // Opens the link once (false with the reason logged when it cannot yet: the reader
  // thread keeps trying), then starts the reader thread.
  bool start(FrameHandler on_frame);
  void stop();
  // A whole frame; false when the link is down or has no peer yet (udpin). No allocation.
  bool write(const std::uint8_t* data, std::size_t size);
  bool is_open() const { return link_->is_open(); }
  std::string describe() const { return link_->describe(); }

 private:
  void run();
  void reopen();

  std::unique_ptr<mavlink::Link> link_;
  mavlink::StreamParser parser_;
  FrameHandler on_frame_;
  std::atomic<bool> stop_{false};
  bool was_open_ = false;
  double lost_at_s_ = 0.0;
  double next_open_s_ = 0.0;
  double next_still_down_log_s_ = 0.0;
  std::thread thread_;
};

}  // namespace cover::fc_bridge
