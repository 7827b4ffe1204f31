#pragma once

#include <string>

namespace cover::launch {

// `count: N` in a launch file's process: one description started N times, copy i
// (0..N-1) with `{i}` replaced by i and `{i+K}` by i + K (K a non-negative integer), in its
// name, executable, args, env values, netns and identity. What makes a fleet of sixteen
// UAV agents one entry instead of sixteen.
inline constexpr int kMaxProcessCount = 256;

// `text` with every `{i}` / `{i+K}` replaced for copy `index`; other placeholders and the
// `{{` / `}}` escapes are left as they are. Throws std::invalid_argument on `{i+...}` whose
// offset is not a non-negative integer.
std::string substitute_index(const std::string& text, int index);

// True when `text` names `{i}` or `{i+K}`.
bool uses_index(const std::string& text);

}  // namespace cover::launch
