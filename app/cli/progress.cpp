#include "app/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled && isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() {
  Done();
}

bool ProgressLine::Due(bool force) {
  if (!enabled_) return false;
  const auto now = std::chrono::steady_clock::now();
  if (Seconds(now - start_) < 0.5 && !force) return false;
  if (shown_ && Seconds(now - last_) < 0.1 && !force) return false;
  last_ = now;
  return true;
}

void ProgressLine::Print(const std::string& line) {
  // Pad over a longer previous line; the cursor stays on the line (\r, no newline).
  const std::size_t pad = last_len_ > line.size() ? last_len_ - line.size() : 0;
  std::fputs(("\r" + line + std::string(pad, ' ')).c_str(), stderr);
  std::fflush(stderr);
  last_len_ = line.size();
  shown_ = true;
}

void ProgressLine::Update(double fraction, const std::string& detail) {
  if (!Due(false)) return;
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int width = 24, filled = static_cast<int>(fraction * width);
  std::string bar = "[" + std::string(filled, '=') + (filled < width ? ">" : "") +
                    std::string(std::max(0, width - filled - 1), ' ') + "]";
  const std::string pct = sim::Sprintf(" %3d%%  ", static_cast<int>(fraction * 100));
  const double elapsed = Seconds(std::chrono::steady_clock::now() - start_);
  std::string left = "";
  if (fraction > 0.01 && elapsed > 0.25)  // shown with the first line (after 0.5 s)
    left = "  " + sim::FormatClock(elapsed * (1 - fraction) / fraction) + " left";
  Print(bar + pct + detail + left);
}

void ProgressLine::Status(const std::string& detail) {
  if (!Due(true)) return;
  Print(detail + "  (" + sim::FormatClock(Seconds(std::chrono::steady_clock::now() - start_)) + " so far)");
}

void ProgressLine::Done() {
  if (!enabled_ || !shown_) return;
  std::fputs(("\r" + std::string(last_len_, ' ') + "\r").c_str(), stderr);
  std::fflush(stderr);
  shown_ = false;
  last_len_ = 0;
}

}  // namespace formsim::app
