#include "cover/vrpn/protocol.hpp"

#include <cstring>

namespace cover::vrpn {

std::array<std::uint8_t, kCookieBytes> make_cookie() {
  std::array<std::uint8_t, kCookieBytes> cookie{};
  std::memcpy(cookie.data(), kMagic.data(), kMagic.size());
  cookie[16] = ' ';
  cookie[17] = ' ';
  cookie[18] = '0';
  return cookie;
}

CookieCheck check_cookie(const std::uint8_t* cookie) {
  // "vrpn: ver. 07" is the part that must match; ".35" is the minor version.
  const std::size_t major_end = kMagic.rfind('.');
  if (std::memcmp(cookie, kMagic.data(), major_end) != 0) return CookieCheck::Mismatch;
  if (std::memcmp(cookie, kMagic.data(), kMagic.size()) != 0) return CookieCheck::MinorMismatch;
  return CookieCheck::Match;
}

}  // namespace cover::vrpn
