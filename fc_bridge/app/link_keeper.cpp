#include "link_keeper.hpp"

#include <spdlog/spdlog.h>

#include <array>
#include <chrono>

#include "cover/clock/clock.hpp"

namespace cover::fc_bridge {
namespace {
constexpr double kReopenPeriod_s = 0.2;
constexpr double kStillDownLogPeriod_s = 30.0;
constexpr std::chrono::milliseconds kReadWait{20};
double monotonic_s() {
  return clock::ns_to_s(clock::monotonic_ns());
}
}  // namespace

LinkKeeper::LinkKeeper(std::unique_ptr<mavlink::Link> link, mavlink::ParserOptions parser_options)
    : link_(std::move(link)), parser_(std::move(parser_options)) {}

LinkKeeper::~LinkKeeper() {
  stop();
}

bool LinkKeeper::start(FrameHandler on_frame) {
  on_frame_ = std::move(on_frame);
  was_open_ = link_->open();
  if (was_open_) {
    spdlog::info("link {} open", link_->describe());
  } else {
    spdlog::warn("link {} cannot open yet ({}); trying again every {:.1f} s", link_->describe(),
                 link_->last_error(), kReopenPeriod_s);
    lost_at_s_ = monotonic_s();
    next_still_down_log_s_ = lost_at_s_ + kStillDownLogPeriod_s;
  }
  thread_ = std::thread([this] { run(); });
  return was_open_;
}

void LinkKeeper::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  link_->close();
}

bool LinkKeeper::write(const std::uint8_t* data, std::size_t size) {
  return link_->write(data, size);
}

void LinkKeeper::run() {
  std::array<std::uint8_t, 2048> buffer{};
  while (!stop_) {
    if (!link_->is_open()) {
      reopen();
      continue;
    }
    const std::size_t n = link_->read(buffer.data(), buffer.size(), kReadWait);
    if (n > 0) {
      parser_.feed(buffer.data(), n,
                   [this](const mavlink::Frame& frame) { on_frame_(frame, parser_.stats()); });
    }
    if (!link_->is_open()) {
      spdlog::error("link {} LOST: {}; opening it again every {:.1f} s", link_->describe(),
                    link_->last_error(), kReopenPeriod_s);
      was_open_ = false;
      lost_at_s_ = monotonic_s();
      next_open_s_ = lost_at_s_ + kReopenPeriod_s;
      next_still_down_log_s_ = lost_at_s_ + kStillDownLogPeriod_s;
    }
  }
}

void LinkKeeper::reopen() {
  const double now = monotonic_s();
  if (now < next_open_s_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return;
  }
  next_open_s_ = now + kReopenPeriod_s;
  if (link_->open()) {
    parser_.reset();  // a partial frame from before the loss is gone
    spdlog::info("link {} open again after {:.1f} s", link_->describe(), now - lost_at_s_);
    was_open_ = true;
    return;
  }
  if (now >= next_still_down_log_s_) {
    spdlog::warn("link {} still down after {:.0f} s: {}", link_->describe(), now - lost_at_s_,
                 link_->last_error());
    next_still_down_log_s_ = now + kStillDownLogPeriod_s;
  }
}

}  // namespace cover::fc_bridge
