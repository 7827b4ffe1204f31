#include "cover/foxglove/subscriber_client.hpp"

#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

#include "cover/foxglove/protocol.hpp"

namespace cover::foxglove {
namespace {

using WsClient = websocketpp::client<websocketpp::config::asio_client>;
using Hdl = websocketpp::connection_hdl;

constexpr auto kRetryPeriod = std::chrono::milliseconds(200);

}  // namespace

class SubscriberClient::Impl {
 public:
  explicit Impl(std::string uri) : uri_(std::move(uri)) {
    ws_.clear_access_channels(websocketpp::log::alevel::all);
    ws_.clear_error_channels(websocketpp::log::elevel::all);
    ws_.init_asio();
    ws_.start_perpetual();
    ws_.set_message_handler([this](Hdl hdl, WsClient::message_ptr message) {
      on_message(hdl, message);
    });
    ws_.set_open_handler([this](Hdl) { connected_ = true; });
    ws_.set_fail_handler([this](Hdl) { retry(); });
    ws_.set_close_handler([this](Hdl) {
      connected_ = false;
      retry();
    });
    connect();
    thread_ = std::thread([this] { ws_.run(); });
  }

  ~Impl() { stop(); }

  void stop() {
    if (stopping_.exchange(true)) return;
    ws_.stop_perpetual();
    ws_.stop();
    if (thread_.joinable()) thread_.join();
  }

  Counts counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    Counts out = counts_;
    out.connected = connected_;
    return out;
  }

 private:
  void connect() {
    if (stopping_) return;
    websocketpp::lib::error_code error;
    auto connection = ws_.get_connection(uri_, error);
    if (error) return;  // a malformed URI: nothing to retry
    connection->add_subprotocol(kSubprotocolV1);
    ws_.connect(connection);
  }

  void retry() {
    if (stopping_) return;
    ws_.set_timer(kRetryPeriod.count(), [this](const websocketpp::lib::error_code&) { connect(); });
  }

  void on_message(Hdl hdl, const WsClient::message_ptr& message) {
    if (message->get_opcode() == websocketpp::frame::opcode::binary) {
      const auto& payload = message->get_payload();
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_.messages;
      counts_.bytes +=
          payload.size() > kMessageDataHeaderBytes ? payload.size() - kMessageDataHeaderBytes : 0;
      return;
    }
    const auto json = nlohmann::json::parse(message->get_payload(), nullptr, false);
    if (!json.is_object() || json.value("op", "") != "advertise") return;
    nlohmann::json subscribe{{"op", "subscribe"}, {"subscriptions", nlohmann::json::array()}};
    for (const auto& channel : json.value("channels", nlohmann::json::array())) {
      if (!channel.contains("id") || !channel["id"].is_number_unsigned()) continue;
      subscribe["subscriptions"].push_back({{"id", next_id_++}, {"channelId", channel["id"]}});
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      counts_.channels_advertised += subscribe["subscriptions"].size();
    }
    websocketpp::lib::error_code error;
    ws_.send(hdl, subscribe.dump(), websocketpp::frame::opcode::text, error);
  }

  std::string uri_;
  WsClient ws_;
  std::thread thread_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> connected_{false};
  std::uint32_t next_id_ = 1;  // the I/O thread's alone
  mutable std::mutex mutex_;
  Counts counts_;
};

SubscriberClient::SubscriberClient(std::string uri) : impl_(std::make_unique<Impl>(std::move(uri))) {}
SubscriberClient::~SubscriberClient() = default;
SubscriberClient::Counts SubscriberClient::counts() const { return impl_->counts(); }
void SubscriberClient::stop() { impl_->stop(); }

}  // namespace cover::foxglove
