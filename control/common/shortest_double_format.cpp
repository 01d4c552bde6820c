#include "control/common/shortest_double_format.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <strings.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>

namespace formsim::control {
namespace {

#ifdef __EMSCRIPTEN__
// Reads `text` (NUL-terminated) with strtod: true when it is all one number in range.
bool StrtodWhole(const char* text, double* out) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE) return false;
  *out = v;
  return true;
}
#endif

}  // namespace

char* ToCharsText(char* first, bool negative, const char* digits, int exponent, double v) {
  const int k = static_cast<int>(std::strlen(digits));
  // Scientific: D[.DDD]e±XX (at least two exponent digits, as to_chars).
  char sci[40];
  int sn = 0;
  sci[sn++] = digits[0];
  if (k > 1) {
    sci[sn++] = '.';
    std::memcpy(sci + sn, digits + 1, static_cast<std::size_t>(k - 1));
    sn += k - 1;
  }
  sci[sn++] = 'e';
  sci[sn++] = exponent < 0 ? '-' : '+';
  const int e = exponent < 0 ? -exponent : exponent;
  if (e >= 100) sci[sn++] = static_cast<char>('0' + e / 100);
  sci[sn++] = static_cast<char>('0' + e / 10 % 10);
  sci[sn++] = static_cast<char>('0' + e % 10);
  // Fixed, and its length; the shorter form wins, fixed on a tie.
  char* out = first;
  if (negative) *out++ = '-';
  if (exponent >= k - 1 && std::fabs(v) >= 9007199254740992.0) {
    // From 2^53 on, to_chars writes fixed form as printf's %f does, every digit exact
    // (1234567890123456768, not the shortest digits padded with zeros).
    char whole[400];
    const auto r = fmt::format_to_n(whole, sizeof whole, FMT_COMPILE("{:.0f}"), std::fabs(v));
    const int wn = static_cast<int>(r.size);
    if (wn <= sn) {
      std::memcpy(out, whole, static_cast<std::size_t>(wn));
      return out + wn;
    }
  } else {
    const int fixed_len = exponent >= k - 1 ? exponent + 1 : exponent >= 0 ? k + 1 : k + 1 - exponent;
    if (fixed_len <= sn) {
      if (exponent >= k - 1) {
        // A whole number below 2^53 is exactly its shortest digits padded with zeros.
        std::memcpy(out, digits, static_cast<std::size_t>(k));
        std::memset(out + k, '0', static_cast<std::size_t>(exponent - (k - 1)));
      } else if (exponent >= 0) {
        std::memcpy(out, digits, static_cast<std::size_t>(exponent + 1));
        out[exponent + 1] = '.';
        std::memcpy(out + exponent + 2, digits + exponent + 1,
                    static_cast<std::size_t>(k - exponent - 1));
      } else {
        out[0] = '0';
        out[1] = '.';
        std::memset(out + 2, '0', static_cast<std::size_t>(-exponent - 1));
        std::memcpy(out + 1 - exponent, digits, static_cast<std::size_t>(k));
      }
      return out + fixed_len;
    }
  }
  std::memcpy(out, sci, static_cast<std::size_t>(sn));
  return out + sn;
}

char* WriteShortestDoubleByFmt(char* first, char* last, double v) {
  (void)last;
  const bool negative = std::signbit(v);
  if (!std::isfinite(v)) {
    // As std::to_chars: "inf", "-inf", "nan" or "-nan" (Dragonbox takes finite values only).
    const char* word = std::isnan(v) ? (negative ? "-nan" : "nan") : (negative ? "-inf" : "inf");
    const std::size_t n = std::strlen(word);
    std::memcpy(first, word, n);
    return first + n;
  }
  if (v == 0) return ToCharsText(first, negative, "0", 0, v);
  // {fmt}'s Dragonbox: the shortest significand that reads back to `v` (trailing zeros
  // removed) and its power of ten. Called directly, not through fmt::format("{}"), whose text
  // would only be taken apart again: the page writes every CSV cell through here.
  const auto d = fmt::detail::dragonbox::to_decimal(std::fabs(v));
  const fmt::format_int significand(d.significand);
  return ToCharsText(first, negative, significand.c_str(),
                     d.exponent + static_cast<int>(significand.size()) - 1, v);
}

bool ReadWholeDouble(const char* first, const char* last, double* out) {
#ifndef __EMSCRIPTEN__
  double v = 0;
  const auto res = std::from_chars(first, last, v);
  if (res.ec != std::errc() || res.ptr != last) return false;
  *out = v;
  return true;
#else
  {
    // from_chars' grammar: [-] then digits with an optional point, an optional exponent, or
    // inf / infinity / nan; strtod would also take spaces, '+' and hexadecimal.
    const std::string text(first, last);
    const char* p = text.c_str();
    if (*p == '-') ++p;
    bool number = false;
    for (; *p >= '0' && *p <= '9'; ++p) number = true;
    if (*p == '.')
      for (++p; *p >= '0' && *p <= '9'; ++p) number = true;
    if (number && (*p == 'e' || *p == 'E')) {
      ++p;
      if (*p == '+' || *p == '-') ++p;
      if (!(*p >= '0' && *p <= '9')) return false;
      while (*p >= '0' && *p <= '9') ++p;
    }
    if (!number) {
      const char* word = text.c_str() + (text[0] == '-' ? 1 : 0);
      for (const char* w : {"inf", "infinity", "nan"})
        if (strcasecmp(word, w) == 0) return StrtodWhole(text.c_str(), out);
      return false;
    }
    if (*p != '\0') return false;
    return StrtodWhole(text.c_str(), out);
  }
#endif
}

}  // namespace formsim::control
