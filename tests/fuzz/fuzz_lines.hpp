#pragma once
/// \file The fuzz harnesses' input as lines: the first byte is the harness's own choice (which
/// scenario), the rest is split at '\n' into at most `max_lines` lines.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace formsim::fuzz {

inline std::vector<std::string> InputLines(const std::uint8_t* data, std::size_t size,
                                           std::size_t max_lines) {
  std::vector<std::string> lines;
  std::string cur;
  for (std::size_t i = 1; i < size; ++i) {
    if (data[i] == '\n') {
      lines.push_back(cur);
      cur.clear();
    } else {
      cur += static_cast<char>(data[i]);
    }
  }
  if (!cur.empty()) lines.push_back(cur);
  if (lines.size() > max_lines) lines.resize(max_lines);
  return lines;
}

}  // namespace formsim::fuzz
