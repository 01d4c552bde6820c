#pragma once
/// \file The shortest text that reads back to the same double, and its reading, as
/// std::to_chars / std::from_chars give them for a double (no format argument): the CSV cells,
/// summary numbers and every value formsim writes for reading back. Part of the formatting
/// module (number_format.hpp is its front). On the desktop this is std::to_chars itself
/// (libstdc++'s Ryu). The browser page's libc++ (emscripten 3.1.6) has no floating-point
/// to_chars: there the shortest digits come from {fmt}'s Dragonbox and ToCharsText lays them
/// out as to_chars does, so the page's CSVs are the desktop's byte for byte (tested against
/// std::to_chars on the desktop and in the page). Measured in the page (7 Dec, 2 cores):
/// formation_traj2_ukf with its CSV at 573x real time this way, 268x with JavaScript's
/// Number::toString digits before.

#include <charconv>

namespace formsim::control {

/// The text of `v` as std::to_chars writes it, from its shortest digits `digits` (no sign, no
/// leading or trailing zeros, "0" for zero) and the decimal exponent of their first digit:
/// fixed or scientific, whichever is shorter (fixed on a tie; a whole number of 2^53 or more in
/// fixed form with every digit exact). Returns the end of the text (at most 24 characters).
char* ToCharsText(char* first, bool negative, const char* digits, int exponent, double v);

/// std::to_chars(first, last, v)'s text for `v` made from {fmt}'s shortest digits
/// (Dragonbox; the page's way); "inf", "-inf", "nan" or "-nan" as to_chars for the others. `last - first` must be at least 24. Allocates nothing.
char* WriteShortestDoubleByFmt(char* first, char* last, double v);

/// Writes `v` (finite) as std::to_chars(first, last, v) does: the shortest digits that read
/// back to `v` (the closest such). `last - first` must be at least 24. Allocates nothing.
inline char* WriteShortestDouble(char* first, char* last, double v) {
#ifdef __EMSCRIPTEN__
  return WriteShortestDoubleByFmt(first, last, v);
#else
  return std::to_chars(first, last, v).ptr;
#endif
}

/// Reads all of [first, last) as std::from_chars reads a double (no leading '+' or space, no
/// hexadecimal): true and `*out` when every character was taken and the value is in range.
bool ReadWholeDouble(const char* first, const char* last, double* out);

}  // namespace formsim::control
