#include "cover/sim/mocap/vrpn_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <stdexcept>

#include "cover/sim/mocap/server_wire.hpp"

namespace cover::sim::mocap {
namespace {

constexpr std::size_t kMaxClientMessage = 4096;

std::int32_t read_be32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return static_cast<std::int32_t>(ntohl(v));
}

}  // namespace

struct VrpnServer::Client {
  int fd = -1;
  std::string peer;
  bool ready = false;  // its cookie came and our descriptions went
  std::vector<std::uint8_t> in;
  std::vector<std::uint8_t> pending;  // bytes its socket has not taken yet
  std::map<std::int32_t, std::string> senders;
  std::int32_t ping_type = INT32_MIN;
};

VrpnServer::VrpnServer(ServerOptions options) : options_(std::move(options)) {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(options_.port);
  if (::inet_pton(AF_INET, options_.bind_address.c_str(), &address.sin_addr) != 1) {
    ::close(listen_fd_);
    throw std::runtime_error("VRPN server: bad bind address '" + options_.bind_address + "'");
  }
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listen_fd_, 8) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listen_fd_);
    throw std::runtime_error("VRPN server: cannot listen on " + options_.bind_address + ":" +
                             std::to_string(options_.port) + ": " + why);
  }
  socklen_t length = sizeof address;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length);
  port_ = ntohs(address.sin_port);
  if (::pipe2(wake_pipe_, O_CLOEXEC | O_NONBLOCK) != 0) {
    ::close(listen_fd_);
    throw std::runtime_error("VRPN server: pipe: " + std::string(std::strerror(errno)));
  }
  frame_bytes_.reserve(options_.bodies.size() * 96);
  thread_ = std::thread([this] { run(); });
}

VrpnServer::~VrpnServer() {
  stop_ = true;
  const char byte = 0;
  [[maybe_unused]] const ssize_t n = ::write(wake_pipe_[1], &byte, 1);
  thread_.join();
  for (auto& client : clients_) ::close(client->fd);
  ::close(listen_fd_);
  ::close(wake_pipe_[0]);
  ::close(wake_pipe_[1]);
}

std::size_t VrpnServer::ready_clients() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<std::size_t>(std::count_if(
      clients_.begin(), clients_.end(), [](const auto& c) { return c->ready && c->fd >= 0; }));
}

bool VrpnServer::wait_for_clients(std::size_t count, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return ready_changed_.wait_for(lock, timeout, [&] {
    return static_cast<std::size_t>(
               std::count_if(clients_.begin(), clients_.end(),
                             [](const auto& c) { return c->ready && c->fd >= 0; })) >= count;
  });
}

ServerStats VrpnServer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void VrpnServer::send_frame(std::int64_t capture_ns, const std::vector<WirePose>& poses) {
  std::lock_guard<std::mutex> lock(mutex_);
  frame_bytes_.clear();
  const wire::Stamp stamp = wire::stamp_of(capture_ns);
  const std::size_t n = std::min(poses.size(), options_.bodies.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!poses[i].present) continue;
    wire::put_pos_quat(frame_bytes_, static_cast<std::int32_t>(i), stamp, poses[i].position,
                       poses[i].quaternion_xyzw);
  }
  ++stats_.frames;
  if (frame_bytes_.empty()) return;
  for (auto& client : clients_) {
    if (client->ready && client->fd >= 0)
      write_to(*client, frame_bytes_.data(), frame_bytes_.size());
  }
}

void VrpnServer::write_to(Client& client, const std::uint8_t* data, std::size_t size) {
  if (client.pending.empty()) {
    const ssize_t n = ::send(client.fd, data, size, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      drop(client, "send failed");
      return;
    }
    const std::size_t sent = n > 0 ? static_cast<std::size_t>(n) : 0;
    data += sent;
    size -= sent;
  }
  if (size == 0) return;
  if (client.pending.size() + size > options_.max_pending_bytes) {
    drop(client, "too slow (its socket took nothing for a while)");
    return;
  }
  client.pending.insert(client.pending.end(), data, data + size);
}

void VrpnServer::flush(Client& client) {
  if (client.fd < 0 || client.pending.empty()) return;
  const ssize_t n =
      ::send(client.fd, client.pending.data(), client.pending.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  if (n > 0) {
    client.pending.erase(client.pending.begin(), client.pending.begin() + n);
  } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
    drop(client, "send failed");
  }
}

void VrpnServer::drop(Client& client, const char* why) {
  if (client.fd < 0) return;
  spdlog::info("VRPN server: client {} gone ({})", client.peer, why);
  ::close(client.fd);
  client.fd = -1;
  ++stats_.dropped;
  ready_changed_.notify_all();
}

void VrpnServer::accept_clients() {
  for (;;) {
    sockaddr_in peer{};
    socklen_t length = sizeof peer;
    const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&peer), &length,
                             SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    auto client = std::make_unique<Client>();
    client->fd = fd;
    char text[INET_ADDRSTRLEN] = {};
    ::inet_ntop(AF_INET, &peer.sin_addr, text, sizeof text);
    client->peer = std::string(text) + ":" + std::to_string(ntohs(peer.sin_port));
    std::vector<std::uint8_t> cookie;
    wire::put_cookie(cookie);
    write_to(*client, cookie.data(), cookie.size());
    ++stats_.accepted;
    spdlog::info("VRPN server: client {} connected", client->peer);
    clients_.push_back(std::move(client));
  }
}

void VrpnServer::on_client_message(Client& client, const std::uint8_t* message) {
  const std::int32_t length = read_be32(message);
  const std::int32_t sender = read_be32(message + 12);
  const std::int32_t type = read_be32(message + 16);
  const std::uint8_t* payload = message + wire::kHeaderSize;
  const std::size_t payload_size = static_cast<std::size_t>(length) - wire::kHeaderSize;
  if ((type == -1 || type == -2) && payload_size > 4) {
    const std::int32_t name_size = read_be32(payload);
    if (name_size < 1 || static_cast<std::size_t>(name_size) > payload_size - 4) return;
    const std::string name(
        reinterpret_cast<const char*>(payload + 4),
        strnlen(reinterpret_cast<const char*>(payload + 4), static_cast<std::size_t>(name_size)));
    if (type == -1) client.senders[sender] = name;
    if (type == -2 && name == wire::kTypeNames[wire::kPing]) client.ping_type = sender;
    return;
  }
  if (type != client.ping_type) return;
  const auto name = client.senders.find(sender);
  if (name == client.senders.end()) return;
  const auto& bodies = options_.bodies;
  const auto body = std::find(bodies.begin(), bodies.end(), name->second);
  if (body == bodies.end()) return;
  std::vector<std::uint8_t> pong;
  wire::put_message(pong, static_cast<std::int32_t>(body - bodies.begin()), wire::kPong,
                    {read_be32(message + 4), read_be32(message + 8)}, nullptr, 0);
  write_to(client, pong.data(), pong.size());
  ++stats_.pongs;
}

void VrpnServer::read_client(Client& client) {
  std::uint8_t chunk[4096];
  for (;;) {
    const ssize_t n = ::recv(client.fd, chunk, sizeof chunk, MSG_DONTWAIT);
    if (n == 0) return drop(client, "closed by the client");
    if (n < 0) {
      if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) drop(client, "recv failed");
      return;
    }
    client.in.insert(client.in.end(), chunk, chunk + n);
    if (!client.ready && client.in.size() >= wire::kCookieSize) {
      if (std::memcmp(client.in.data(), wire::kVersion, 13) != 0) {
        return drop(client, "not a VRPN 07.x client");
      }
      client.in.erase(client.in.begin(), client.in.begin() + wire::kCookieSize);
      std::vector<std::uint8_t> descriptions;
      for (std::size_t i = 0; i < options_.bodies.size(); ++i) {
        wire::put_description(descriptions, -1, static_cast<std::int32_t>(i), options_.bodies[i]);
      }
      for (std::int32_t t = 0; t < 4; ++t) {
        wire::put_description(descriptions, -2, t, wire::kTypeNames[t]);
      }
      write_to(client, descriptions.data(), descriptions.size());
      client.ready = client.fd >= 0;
      ready_changed_.notify_all();
    }
    while (client.ready && client.in.size() >= wire::kHeaderSize) {
      const std::int32_t length = read_be32(client.in.data());
      if (length < static_cast<std::int32_t>(wire::kHeaderSize) ||
          length > static_cast<std::int32_t>(kMaxClientMessage)) {
        return drop(client, "a message length out of bounds");
      }
      const std::size_t whole = wire::kHeaderSize + (length - wire::kHeaderSize + 7) / 8 * 8;
      if (client.in.size() < whole) break;
      on_client_message(client, client.in.data());
      client.in.erase(client.in.begin(), client.in.begin() + static_cast<std::ptrdiff_t>(whole));
    }
    if (client.fd < 0) return;
  }
}

void VrpnServer::run() {
  std::vector<pollfd> fds;
  while (!stop_) {
    fds.clear();
    fds.push_back({wake_pipe_[0], POLLIN, 0});
    fds.push_back({listen_fd_, POLLIN, 0});
    {
      std::lock_guard<std::mutex> lock(mutex_);
      clients_.erase(
          std::remove_if(clients_.begin(), clients_.end(), [](const auto& c) { return c->fd < 0; }),
          clients_.end());
      for (const auto& c : clients_) {
        fds.push_back({c->fd, static_cast<short>(POLLIN | (c->pending.empty() ? 0 : POLLOUT)), 0});
      }
    }
    // Short: a frame written meanwhile may leave bytes pending that need POLLOUT.
    if (::poll(fds.data(), fds.size(), 10) < 0) continue;
    std::lock_guard<std::mutex> lock(mutex_);
    if (fds[1].revents & POLLIN) accept_clients();
    for (std::size_t i = 2; i < fds.size(); ++i) {
      for (auto& c : clients_) {
        if (c->fd != fds[i].fd || c->fd < 0) continue;
        if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) read_client(*c);
        flush(*c);
      }
    }
  }
}

}  // namespace cover::sim::mocap
