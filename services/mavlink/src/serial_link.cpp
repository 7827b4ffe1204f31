#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "link_factories.hpp"
#include "serial_baud.hpp"

namespace cover::mavlink::detail {
namespace {

// How long a write waits for room in the port's output buffer before it gives the frame
// up: a frame takes 3 ms at 921600 baud, far less than a full kernel buffer drains in.
constexpr int kWriteRoomWaitMs = 20;

// Raw 8N1 at `speed`, no flow control, reads return what is there (VMIN 0, VTIME 0).
bool configure(int fd, speed_t speed, const char*& what) {
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    what = "not a serial port (tcgetattr)";
    return false;
  }
  ::cfmakeraw(&tio);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
  tio.c_cflag |= CS8 | CLOCAL | CREAD;
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetspeed(&tio, speed) != 0) {
    what = "cfsetspeed";
    return false;
  }
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    what = "tcsetattr";
    return false;
  }
  ::tcflush(fd, TCIOFLUSH);  // bytes from before we owned the port belong to nobody
  return true;
}

class SerialLink final : public Link {
 public:
  SerialLink(std::string device, int baud)
      : device_(std::move(device)),
        baud_(baud),
        description_("serial://" + device_ + ":" + std::to_string(baud)) {}
  ~SerialLink() override { close(); }

  bool open() override {
    if (is_open()) return true;
    const auto speed = termios_speed(baud_);
    if (!speed) return fail("baud rate not supported", 0);
    const int fd = ::open(device_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return fail("cannot open the device", errno);
    const char* what = "";
    if (!configure(fd, *speed, what)) {
      const int saved = errno;
      ::close(fd);
      return fail(what, saved);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    fd_ = fd;
    error_[0] = '\0';
    return true;
  }

  void close() override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  bool is_open() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return fd_ >= 0;
  }

  std::size_t read(std::uint8_t* buffer, std::size_t capacity,
                   std::chrono::milliseconds timeout) override {
    const int fd = current_fd();  // only the reading thread opens and closes
    if (fd < 0) return 0;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
    if (ready < 0) return 0;  // EINTR
    if (ready == 0) return 0;
    if ((p.revents & POLLIN) != 0) {
      const ssize_t n = ::read(fd, buffer, capacity);
      if (n > 0) return static_cast<std::size_t>(n);
      if (n < 0 && (errno == EAGAIN || errno == EINTR) && (p.revents & POLLHUP) == 0) return 0;
      lose(n == 0 ? "end of file (device gone)" : "read failed", n == 0 ? 0 : errno);
      return 0;
    }
    if ((p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) lose("device hung up", 0);
    return 0;
  }

  bool write(const std::uint8_t* data, std::size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (fd_ < 0) return fail_locked("link closed", 0);
    std::size_t done = 0;
    int waited_ms = 0;
    while (done < size) {
      const ssize_t n = ::write(fd_, data + done, size - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
        continue;
      }
      if (n < 0 && errno != EAGAIN && errno != EINTR) return fail_locked("write failed", errno);
      if (waited_ms >= kWriteRoomWaitMs) return fail_locked("output buffer full", 0);
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 1);
      ++waited_ms;
    }
    return true;
  }

  std::string describe() const override { return description_; }

  std::string last_error() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_.data();
  }

 private:
  int current_fd() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return fd_;
  }

  void lose(const char* why, int error_number) {
    std::lock_guard<std::mutex> lock(mutex_);
    fail_locked(why, error_number);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  bool fail(const char* why, int error_number) {
    std::lock_guard<std::mutex> lock(mutex_);
    return fail_locked(why, error_number);
  }

  // A fixed buffer: a failing write must not allocate.
  bool fail_locked(const char* why, int error_number) {
    if (error_number != 0) {
      std::snprintf(error_.data(), error_.size(), "%s: %s: %s", description_.c_str(), why,
                    std::strerror(error_number));
    } else {
      std::snprintf(error_.data(), error_.size(), "%s: %s", description_.c_str(), why);
    }
    return false;
  }

  const std::string device_;
  const int baud_;
  const std::string description_;
  mutable std::mutex mutex_;  // guards fd_ against a close while the writer writes
  int fd_ = -1;
  std::array<char, 512> error_{};
};

}  // namespace

std::unique_ptr<Link> make_serial(std::string device, int baud) {
  return std::make_unique<SerialLink>(std::move(device), baud);
}

}  // namespace cover::mavlink::detail
