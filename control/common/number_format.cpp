#include "control/common/number_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <system_error>

#include "control/common/shortest_double_format.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

namespace formsim::control {

void AppendDouble(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  if (std::isinf(v)) {
    out += v > 0 ? "inf" : "-inf";
    return;
  }
  char buf[32];
  out.append(buf, WriteShortestDouble(buf, buf + sizeof buf, v));
}

std::string FormatDouble(double v) {
  std::string s;
  AppendDouble(s, v);
  return s;
}

std::string FormatSignificant(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format(FMT_COMPILE("{:.{}g}"), v, std::clamp(digits, 1, 17));
}

std::string FormatFixed(double v, int decimals, bool trim) {
  if (!std::isfinite(v)) return FormatSignificant(v);
  decimals = std::clamp(decimals, 0, 17);
  // Below half a unit of the last digit the text would read "-0.00": write zero.
  if (std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0.0;
  std::string s = fmt::format(FMT_COMPILE("{:.{}f}"), v, decimals);
  if (trim && s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string FormatScientific(double v, int digits) {
  if (v == 0.0) return "0";
  if (!std::isfinite(v)) return FormatSignificant(v);
  digits = std::clamp(digits, 1, 17);
  int e = static_cast<int>(std::floor(std::log10(std::abs(v))));
  double m = v / std::pow(10.0, e);
  const double unit = std::pow(10.0, -(digits - 1));
  m = std::round(m / unit) * unit;
  // Rounding may carry into a new digit (9.96 -> 10.0): renormalise.
  if (std::abs(m) >= 10.0) m /= 10.0, ++e;
  return Sprintf("%.*f", digits - 1, m) + "e" + std::to_string(e);
}

namespace {

// The decimal exponent of `v` once rounded to `digits` significant digits (9.9996 -> 1).
int RoundedExponent(double v, int digits) {
  int e = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const double unit = std::pow(10.0, e - digits + 1);
  if (std::abs(std::round(v / unit) * unit) >= std::pow(10.0, e + 1)) ++e;
  return e;
}

// Cells between 1e-4 and 1e6 are written with decimals, others with an exponent.
bool CellIsFixed(int exponent) { return exponent >= -4 && exponent < 6; }

}  // namespace

std::string FormatCell(double v, int digits) {
  if (!std::isfinite(v)) return FormatSignificant(v);
  if (v == 0.0) return "0";
  digits = std::clamp(digits, 1, 17);
  if (v == std::floor(v) && std::abs(v) < 1e6) return Sprintf("%.0f", v);
  const int e = RoundedExponent(v, digits);
  if (!CellIsFixed(e)) return FormatScientific(v, digits);
  return FormatFixed(v, std::max(0, digits - 1 - e));
}

std::string FormatMeanSigma(double mean, double sigma, int digits) {
  if (!std::isfinite(sigma) || !std::isfinite(mean)) return FormatCell(mean, digits);
  digits = std::clamp(digits, 1, 17);
  // The decimal place of the mean's last digit (of σ's when the mean is zero).
  const double lead = mean != 0.0 ? mean : sigma;
  if (lead == 0.0) return "0 ± 0";
  const int e = RoundedExponent(lead, digits);
  if (CellIsFixed(e)) {
    const int decimals = std::max(0, digits - 1 - e);
    return FormatFixed(mean, decimals) + " ± " + FormatFixed(sigma, decimals);
  }
  const double scale = std::pow(10.0, e);
  return "(" + FormatFixed(mean / scale, digits - 1) + " ± " + FormatFixed(sigma / scale, digits - 1) +
         ")e" + std::to_string(e);
}

std::string FormatWholeOrShortest(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  return FormatDouble(v);
}

std::string FormatClock(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) seconds = 0;
  // Beyond a century of seconds a clock says nothing more; cap before converting to an integer.
  const long t = std::lround(std::min(seconds, 3.2e9));
  return t >= 3600 ? Sprintf("%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60)
                   : Sprintf("%ld:%02ld", t / 60, t % 60);
}

void Print(std::FILE* out, const char* fmt, ...) {
  std::va_list args;
  va_start(args, fmt);
  std::vfprintf(out, fmt, args);
  va_end(args);
}

std::string FormatSimTime(double t) { return "t = " + FormatFixed(t, 2) + " s"; }

std::string Sprintf(const char* fmt, ...) {
  char buf[256];
  std::va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  if (n < static_cast<int>(sizeof buf)) return buf;
  std::string out(static_cast<std::size_t>(n) + 1, '\0');
  va_start(args, fmt);
  std::vsnprintf(out.data(), out.size(), fmt, args);
  va_end(args);
  out.resize(static_cast<std::size_t>(n));
  return out;
}

void AppendSprintf(std::string& out, const char* fmt, ...) {
  char buf[256];
  std::va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  if (n < 0) return;
  if (n < static_cast<int>(sizeof buf)) {
    out.append(buf, static_cast<std::size_t>(n));
    return;
  }
  const std::size_t at = out.size();
  out.resize(at + static_cast<std::size_t>(n) + 1);
  va_start(args, fmt);
  std::vsnprintf(&out[at], static_cast<std::size_t>(n) + 1, fmt, args);
  va_end(args);
  out.resize(at + static_cast<std::size_t>(n));
}

bool ParseFiniteDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') ++first;  // from_chars refuses a leading '+', YAML and users write it
  double v = 0;
  if (!ReadWholeDouble(first, last, &v) || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

bool ParseInteger(const std::string& text, long long lo, long long hi, long long* out) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') ++first;
  long long v = 0;
  const auto res = std::from_chars(first, last, v);
  if (res.ec != std::errc() || res.ptr != last || v < lo || v > hi) return false;
  *out = v;
  return true;
}

bool ParseUint64(const std::string& text, std::uint64_t* out) {
  if (text.empty() || text[0] < '0' || text[0] > '9') return false;
  std::uint64_t v = 0;
  const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec != std::errc() || res.ptr != text.data() + text.size()) return false;
  *out = v;
  return true;
}

}  // namespace formsim::control
