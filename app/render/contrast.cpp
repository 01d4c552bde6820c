#include "app/render/contrast.hpp"

#include <algorithm>
#include <cmath>

namespace formsim::app {
namespace {

double Linear(float channel) {
  const double c = std::clamp(static_cast<double>(channel), 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

sim::Color Mix(sim::Color a, float e, float t) {
  return {a.r + (e - a.r) * t, a.g + (e - a.g) * t, a.b + (e - a.b) * t, a.a};
}

}  // namespace

double RelativeLuminance(sim::Color c) {
  return 0.2126 * Linear(c.r) + 0.7152 * Linear(c.g) + 0.0722 * Linear(c.b);
}

double ContrastRatio(sim::Color a, sim::Color b) {
  const double la = RelativeLuminance(a), lb = RelativeLuminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

sim::Color Over(sim::Color c, sim::Color bg) {
  const float a = std::clamp(c.a, 0.0f, 1.0f);
  return {c.r * a + bg.r * (1 - a), c.g * a + bg.g * (1 - a), c.b * a + bg.b * (1 - a), 1.0f};
}

sim::Color WithContrast(sim::Color c, sim::Color bg, double ratio) {
  if (ContrastRatio(c, bg) >= ratio) return c;
  // Black reaches 21:1 against white and white against black; the background's luminance
  // where both give the same contrast is about 0.179.
  const float extreme = RelativeLuminance(bg) > 0.179 ? 0.0f : 1.0f;
  float lo = 0.0f, hi = 1.0f;  // the least blend towards `extreme` that reaches `ratio`
  for (int i = 0; i < 24; ++i) {
    const float mid = 0.5f * (lo + hi);
    (ContrastRatio(Mix(c, extreme, mid), bg) >= ratio ? hi : lo) = mid;
  }
  return Mix(c, extreme, hi);
}

}  // namespace formsim::app
