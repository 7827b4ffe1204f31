#include "signing_key_file.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

#include "cover/config/config_error.hpp"

namespace cover::fc_bridge {

mavlink::SigningKey load_signing_key(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw config::ConfigError("--signing-key-file " + path + ": cannot be read");
  std::stringstream content;
  content << file.rdbuf();
  std::string hex;
  for (const char c : content.str()) {
    if (std::isspace(static_cast<unsigned char>(c)) != 0) continue;
    if (std::isxdigit(static_cast<unsigned char>(c)) == 0) {
      throw config::ConfigError("--signing-key-file " + path +
                                ": expected 64 hexadecimal digits (a 32-byte key)");
    }
    hex += c;
  }
  mavlink::SigningKey key;
  if (hex.size() != 2 * key.secret.size()) {
    throw config::ConfigError("--signing-key-file " + path + ": expected 64 hexadecimal digits, " +
                              "found " + std::to_string(hex.size()));
  }
  for (std::size_t i = 0; i < key.secret.size(); ++i) {
    key.secret[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
  }
  return key;
}

}  // namespace cover::fc_bridge
