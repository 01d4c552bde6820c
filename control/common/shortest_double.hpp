#pragma once
/// \file The shortest text that reads back to the same double, and its reading, as
/// std::to_chars / std::from_chars give them for a double (no format argument): the CSV cells,
/// summary numbers and every value formsim writes for reading back. The browser page's C++
/// library (emscripten 3.1.6's libc++) has no floating-point to_chars / from_chars: there the
/// same text is made by ToCharsText from the shortest digits (tested on the desktop against
/// std::to_chars, with ShortestDoubleByPrintf finding the digits).

#include <charconv>

namespace formsim::control {

/// std::to_chars(first, last, v) for a finite `v`: the shortest digits that read back to `v`
/// (the closest such), written fixed or scientific, whichever is shorter (fixed on a tie; a
/// whole number in fixed form with every digit exact). `last - first` must be at least 24.
/// Found with printf and strtod: a reference, tested against std::to_chars.
char* ShortestDoubleByPrintf(char* first, char* last, double v);

/// The text of `v` as std::to_chars writes it, from its shortest digits `digits` (no sign, no
/// leading or trailing zeros, "0" for zero) and the decimal exponent of their first digit.
/// Returns the end of the text (at most 24 characters for a double).
char* ToCharsText(char* first, bool negative, const char* digits, int exponent, double v);

#ifdef __EMSCRIPTEN__
/// The browser page's shortest digits come from JavaScript's Number::toString (the shortest,
/// closest digits by the ECMAScript spec, and fast), since musl's printf and strtod emulate a
/// 128-bit long double in WebAssembly: defined in app/web/shortest_double_web.cpp.
char* ShortestDoubleWeb(char* first, char* last, double v);
#endif

/// Writes `v` (finite) as std::to_chars does.
inline char* WriteShortestDouble(char* first, char* last, double v) {
#ifdef __EMSCRIPTEN__
  return ShortestDoubleWeb(first, last, v);
#else
  return std::to_chars(first, last, v).ptr;
#endif
}

/// Reads all of [first, last) as std::from_chars reads a double (no leading '+' or space, no
/// hexadecimal): true and `*out` when every character was taken and the value is in range.
bool ReadWholeDouble(const char* first, const char* last, double* out);

}  // namespace formsim::control
