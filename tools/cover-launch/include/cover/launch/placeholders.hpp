#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cover::launch {

// Values of the `{name}` placeholders of launch-file arguments.
using PlaceholderValues = std::map<std::string, std::string>;

// The placeholder names in `arg`, in order. `{{` and `}}` stand for literal braces.
// Throws std::invalid_argument on an unmatched brace or an empty name.
std::vector<std::string> placeholder_names(const std::string& arg);

// `arg` with its placeholders replaced; nullopt when one of them is empty, so that
// "--seed={seed}" disappears instead of becoming "--seed=". Throws std::invalid_argument
// naming a placeholder that has no value.
std::optional<std::string> expand_argument(const std::string& arg, const PlaceholderValues& values);

// Every argument expanded; dropped ones are left out.
std::vector<std::string> expand_arguments(const std::vector<std::string>& args,
                                          const PlaceholderValues& values);

}  // namespace cover::launch
