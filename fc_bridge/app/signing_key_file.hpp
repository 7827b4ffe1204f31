#pragma once

#include <string>

#include "cover/mavlink/signing.hpp"

namespace cover::fc_bridge {

// The MAVLink signing secret from a file: 64 hexadecimal digits (32 bytes; whitespace and
// line breaks ignored). Throws config::ConfigError naming the file and what is wrong.
mavlink::SigningKey load_signing_key(const std::string& path);

}  // namespace cover::fc_bridge
