#include "cover/launch/placeholders.hpp"

#include <stdexcept>

namespace cover::launch {
namespace {

// One piece of an argument: literal text, or the name of a placeholder.
struct Piece {
  std::string text;
  bool is_placeholder = false;
};

std::vector<Piece> split(const std::string& arg) {
  std::vector<Piece> pieces{{}};
  for (std::size_t i = 0; i < arg.size(); ++i) {
    const char c = arg[i];
    const bool doubled = i + 1 < arg.size() && arg[i + 1] == c;
    if ((c == '{' || c == '}') && doubled) {
      pieces.back().text += c;
      ++i;
    } else if (c == '{') {
      const auto close = arg.find('}', i + 1);
      if (close == std::string::npos)
        throw std::invalid_argument("unmatched '{' (write {{ for a brace)");
      const std::string name = arg.substr(i + 1, close - i - 1);
      if (name.empty() || name.find('{') != std::string::npos) {
        throw std::invalid_argument("empty or nested placeholder");
      }
      pieces.push_back({name, true});
      pieces.push_back({});
      i = close;
    } else if (c == '}') {
      throw std::invalid_argument("unmatched '}' (write }} for a brace)");
    } else {
      pieces.back().text += c;
    }
  }
  return pieces;
}

}  // namespace

std::vector<std::string> placeholder_names(const std::string& arg) {
  std::vector<std::string> names;
  for (const auto& piece : split(arg)) {
    if (piece.is_placeholder) names.push_back(piece.text);
  }
  return names;
}

std::optional<std::string> expand_argument(const std::string& arg,
                                           const PlaceholderValues& values) {
  std::string expanded;
  for (const auto& piece : split(arg)) {
    if (!piece.is_placeholder) {
      expanded += piece.text;
      continue;
    }
    const auto value = values.find(piece.text);
    if (value == values.end()) {
      throw std::invalid_argument("argument '" + arg + "': unknown placeholder {" + piece.text +
                                  "}");
    }
    if (value->second.empty()) return std::nullopt;
    expanded += value->second;
  }
  return expanded;
}

std::vector<std::string> expand_arguments(const std::vector<std::string>& args,
                                          const PlaceholderValues& values) {
  std::vector<std::string> expanded;
  for (const auto& arg : args) {
    if (auto value = expand_argument(arg, values)) expanded.push_back(std::move(*value));
  }
  return expanded;
}

}  // namespace cover::launch
