#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace cover::sim::mocap {

// A body's pose as the server streams it: in the server's frame and units.
struct WirePose {
  bool present = false;  // false: the body is not in this frame (occluded, dropped)
  double position[3] = {0.0, 0.0, 0.0};
  double quaternion_xyzw[4] = {0.0, 0.0, 0.0, 1.0};
};

struct ServerOptions {
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 3883;        // 0: any free port (port() tells which)
  std::vector<std::string> bodies;  // tracker names, senders 0..n-1
  // A client this far behind (bytes not yet taken by its socket) is dropped.
  std::size_t max_pending_bytes = 1 << 20;
};

struct ServerStats {
  std::uint64_t accepted = 0;
  std::uint64_t dropped = 0;  // clients closed by us (bad bytes, too slow) or by them
  std::uint64_t frames = 0;
  std::uint64_t pongs = 0;
};

// A VRPN tracker server over TCP: each body a sender, each frame one Pos_Quat per present
// body with the frame's capture time. A thread accepts clients, reads their cookies,
// descriptions and pings (answered with pongs); send_frame() writes from the caller's
// thread. Throws std::runtime_error at construction when the port cannot be bound; never
// after.
class VrpnServer {
 public:
  explicit VrpnServer(ServerOptions options);
  ~VrpnServer();
  VrpnServer(const VrpnServer&) = delete;
  VrpnServer& operator=(const VrpnServer&) = delete;

  std::uint16_t port() const { return port_; }
  const std::vector<std::string>& bodies() const { return options_.bodies; }
  // `poses[i]` is body i's (fewer entries: the rest absent).
  void send_frame(std::int64_t capture_ns, const std::vector<WirePose>& poses);
  // Clients past the handshake.
  std::size_t ready_clients() const;
  bool wait_for_clients(std::size_t count, std::chrono::milliseconds timeout) const;
  ServerStats stats() const;

 private:
  struct Client;
  void run();
  void accept_clients();
  void read_client(Client& client);
  void on_client_message(Client& client, const std::uint8_t* message);
  void write_to(Client& client, const std::uint8_t* data, std::size_t size);
  void flush(Client& client);
  void drop(Client& client, const char* why);

  ServerOptions options_;
  int listen_fd_ = -1;
  int wake_pipe_[2] = {-1, -1};
  std::uint16_t port_ = 0;
  mutable std::mutex mutex_;
  mutable std::condition_variable ready_changed_;
  std::vector<std::unique_ptr<Client>> clients_;
  std::vector<std::uint8_t> frame_bytes_;
  ServerStats stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cover::sim::mocap
