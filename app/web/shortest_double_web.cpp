/// \file The page's shortest double text (control/common/shortest_double.hpp): the digits from
/// JavaScript's Number::toString, which the ECMAScript spec makes the shortest that read back
/// and, among those, the closest (as std::to_chars), laid out by ToCharsText as to_chars lays
/// them out. musl's printf and strtod would do it 100 times slower in WebAssembly (their long
/// double is a software binary128).
#include <emscripten.h>

#include <cmath>

#include "control/common/shortest_double.hpp"

// clang-format off (JavaScript)
// Writes the shortest digits of |v| (no leading or trailing zeros, "0" for zero) at `out` with
// a terminating NUL and returns the decimal exponent of the first digit.
EM_JS(int, formsim_js_shortest_digits, (double v, char* out), {
  var s = String(v < 0 ? -v : v);
  var e = s.indexOf("e");
  var mantissa = e < 0 ? s : s.substring(0, e);
  var exp10 = e < 0 ? 0 : parseInt(s.substring(e + 1), 10);
  var dot = mantissa.indexOf(".");
  var whole = dot < 0 ? mantissa : mantissa.substring(0, dot);
  var all = whole + (dot < 0 ? "" : mantissa.substring(dot + 1));
  var lead = 0;
  while (lead < all.length - 1 && all.charCodeAt(lead) == 48) lead++;
  var end = all.length;
  while (end > lead + 1 && all.charCodeAt(end - 1) == 48) end--;
  var digits = all.substring(lead, end);
  for (var i = 0; i < digits.length; ++i) HEAPU8[out + i] = digits.charCodeAt(i);
  HEAPU8[out + digits.length] = 0;
  return whole.length - 1 - lead + exp10;
});
// clang-format on

namespace formsim::control {

char* ShortestDoubleWeb(char* first, char*, double v) {
  char digits[32];
  const int exponent = formsim_js_shortest_digits(v, digits);
  return ToCharsText(first, std::signbit(v), digits, exponent, v);
}

}  // namespace formsim::control
