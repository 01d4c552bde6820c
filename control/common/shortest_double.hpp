#pragma once
/// \file The shortest text that reads back to the same double, and its reading, as
/// std::to_chars / std::from_chars give them for a double (no format argument): the CSV cells,
/// summary numbers and every value formsim writes for reading back. The browser page's C++
/// library (emscripten 3.1.6's libc++) has no floating-point to_chars / from_chars, so there the
/// same text comes from ShortestDoubleByPrintf, which is also compiled and tested on the
/// desktop against std::to_chars.

#include <charconv>

namespace formsim::control {

/// std::to_chars(first, last, v) for a finite `v`: the shortest digits that read back to `v`,
/// written fixed or scientific, whichever is shorter (fixed on a tie). `last - first` must be at
/// least 24. Returns the end of the text.
char* ShortestDoubleByPrintf(char* first, char* last, double v);

/// Writes `v` (finite) as ShortestDoubleByPrintf does, with std::to_chars where it exists.
inline char* WriteShortestDouble(char* first, char* last, double v) {
#ifdef __EMSCRIPTEN__
  return ShortestDoubleByPrintf(first, last, v);
#else
  return std::to_chars(first, last, v).ptr;
#endif
}

/// Reads all of [first, last) as std::from_chars reads a double (no leading '+' or space, no
/// hexadecimal): true and `*out` when every character was taken and the value is in range.
bool ReadWholeDouble(const char* first, const char* last, double* out);

}  // namespace formsim::control
