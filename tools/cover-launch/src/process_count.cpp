#include "cover/launch/process_count.hpp"

#include <optional>
#include <stdexcept>

namespace cover::launch {
namespace {

// The offset K of placeholder name `name` when it is `i` (0) or `i+K`; nullopt for any
// other name.
std::optional<long> index_offset(const std::string& name) {
  if (name == "i") return 0;
  if (name.rfind("i+", 0) != 0) return std::nullopt;
  const std::string digits = name.substr(2);
  if (digits.empty() || digits.size() > 6 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument("{" + name + "}: the offset of {i+K} must be a number 0..999999");
  }
  return std::stol(digits);
}

// Calls `on_index(offset)` for each index placeholder and `on_text(piece)` for the text in
// between (escapes and other placeholders verbatim).
template <typename OnText, typename OnIndex>
void scan(const std::string& text, OnText on_text, OnIndex on_index) {
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    const bool doubled = i + 1 < text.size() && text[i + 1] == c;
    if ((c == '{' || c == '}') && doubled) {
      on_text(text.substr(i, 2));
      i += 2;
      continue;
    }
    const auto close = c == '{' ? text.find('}', i + 1) : std::string::npos;
    if (close == std::string::npos) {
      on_text(std::string(1, c));
      ++i;
      continue;
    }
    const std::string name = text.substr(i + 1, close - i - 1);
    if (const auto offset = index_offset(name)) {
      on_index(*offset);
    } else {
      on_text(text.substr(i, close - i + 1));
    }
    i = close + 1;
  }
}

}  // namespace

std::string substitute_index(const std::string& text, int index) {
  std::string out;
  scan(
      text, [&](const std::string& piece) { out += piece; },
      [&](long offset) { out += std::to_string(index + offset); });
  return out;
}

bool uses_index(const std::string& text) {
  bool found = false;
  scan(
      text, [](const std::string&) {}, [&](long) { found = true; });
  return found;
}

}  // namespace cover::launch
