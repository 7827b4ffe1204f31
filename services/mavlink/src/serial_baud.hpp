#pragma once

#include <termios.h>

#include <optional>

namespace cover::mavlink::detail {

// The termios speed constant of a baud rate, or nullopt when the rate has none: a serial
// link is opened only at one of these, so an unknown rate is refused when the URL is read.
inline std::optional<speed_t> termios_speed(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1152000:
      return B1152000;
    case 1500000:
      return B1500000;
    case 2000000:
      return B2000000;
    case 2500000:
      return B2500000;
    case 3000000:
      return B3000000;
    default:
      return std::nullopt;
  }
}

inline constexpr const char* kSupportedBauds =
    "9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, 576000, 921600, 1000000, "
    "1152000, 1500000, 2000000, 2500000, 3000000";

}  // namespace cover::mavlink::detail
