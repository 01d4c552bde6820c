#include "control/common/shortest_double.hpp"

#include <strings.h>

#include <algorithm>
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

char* ShortestDoubleByPrintf(char* first, char* last, double v) {
  // The shortest digits: every decimal of at most 15 significant digits is its own double
  // (DBL_DIG), so when the value rounded to 15 digits reads back, those digits less their
  // trailing zeros are the shortest; otherwise 16 or 17 digits, correctly rounded (the closest
  // of the candidates, as to_chars chooses).
  // Subnormals carry fewer digits than DBL_DIG: there every length is tried from 1.
  char sci[40];
  int digits = std::fabs(v) < std::numeric_limits<double>::min() && v != 0 ? 1 : 15;
  for (; digits < 17; ++digits) {
    std::snprintf(sci, sizeof sci, "%.*e", digits - 1, v);
    if (std::strtod(sci, nullptr) == v) break;
  }
  if (digits == 17) std::snprintf(sci, sizeof sci, "%.16e", v);
  // sci = [-]D.DDDDe±XX: split into sign, digit string and decimal exponent.
  const char* p = sci;
  const bool negative = *p == '-';
  if (negative) ++p;
  std::string d;
  for (; *p != 'e'; ++p)
    if (*p != '.') d += *p;
  const int exponent = std::atoi(p + 1);
  while (d.size() > 1 && d.back() == '0') d.pop_back();
  char* end = ToCharsText(first, negative, d.c_str(), exponent, v);
  (void)last;
  return end;
}

char* ToCharsText(char* first, bool negative, const char* digits, int exponent, double v) {
  const std::string d = digits;
  const int k = static_cast<int>(d.size());
  std::string scientific = d.substr(0, 1);
  if (k > 1) scientific += "." + d.substr(1);
  char exp_text[16];
  std::snprintf(exp_text, sizeof exp_text, "e%c%02d", exponent < 0 ? '-' : '+',
                exponent < 0 ? -exponent : exponent);
  scientific += exp_text;
  std::string fixed;
  if (exponent >= k - 1 && std::fabs(v) < 9007199254740992.0) {
    // A whole number below 2^53 is exactly its shortest digits padded with zeros.
    fixed = d + std::string(static_cast<std::size_t>(exponent - (k - 1)), '0');
  } else if (exponent >= k - 1) {
    // Above, to_chars writes fixed form as printf's %f, every digit exact
    // (1234567890123456768, not the shortest digits padded with zeros).
    char whole[400];
    std::snprintf(whole, sizeof whole, "%.0f", std::fabs(v));
    fixed = whole;
  } else if (exponent >= 0) {
    fixed = d.substr(0, exponent + 1) + "." + d.substr(exponent + 1);
  } else {
    fixed = "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + d;
  }
  const std::string& best = fixed.size() <= scientific.size() ? fixed : scientific;
  char* out = first;
  if (negative) *out++ = '-';
  std::memcpy(out, best.data(), best.size());
  return out + best.size();
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
