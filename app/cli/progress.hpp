#pragma once
/// \file A progress line on a terminal: "[=====>     ]  42%  t=4.20 s  126/330 frames  1:12 left".
/// Drawn on stderr only when it is a terminal, at most ten times a second, and only once the work
/// has taken half a second (short runs print nothing). The time left is extrapolated from the
/// wall time so far.

#include <chrono>
#include <string>

namespace formsim::app {

class ProgressLine {
 public:
  /// `enabled` false (--quiet) or stderr not a terminal: prints nothing.
  explicit ProgressLine(bool enabled);
  ~ProgressLine();
  /// `fraction` of the work done in [0, 1] and what to say about it ("t=4.20 s  126/330 frames").
  void Update(double fraction, const std::string& detail);
  /// A phase without a fraction ("writing v.gif"): the line shows it with the time spent.
  void Status(const std::string& detail);
  /// Clears the line (before printing results).
  void Done();
  bool enabled() const { return enabled_; }

  /// "1:12", "0:05", "1:02:03".

 private:
  bool Due(bool force);
  void Print(const std::string& line);
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
  bool shown_ = false;
  std::size_t last_len_ = 0;
};

}  // namespace formsim::app
