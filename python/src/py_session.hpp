#pragma once
/// \file The C++ object behind `_core.Session` (and so formsim.Sim): a sim::Session (the one
/// load path of `formsim run` and the window) with the calls Python makes of it. Shared by the
/// bindings of the session (session_binding.cpp) and of its pictures (render_binding.cpp).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/session/session.hpp"

namespace formsim::python {

class PySession {
 public:
  /// `sets`: (key, YAML text) in order, as `--set key=value`; `seed`: as `--seed` (decimal
  /// text); `threads` > 0: threads inside a step (0: the default, all cores).
  PySession(const std::string& name_or_path,
            const std::vector<std::pair<std::string, std::string>>& sets,
            const std::optional<std::string>& seed, int threads);

  sim::Experiment& exp() { return session_->exp(); }
  sim::Session& session() { return *session_; }

  /// Steps until `n` steps were taken, the run ended or the time reached `until` (NaN: no
  /// limit), without the GIL. Returns the number of steps taken, or -(steps + 1) when the run
  /// stopped at a numerical fault during this call (Python raises NumericalFault then, without
  /// asking for the status on every step). Ctrl-C stops the loop (the run stays where it is,
  /// valid) with KeyboardInterrupt.
  long Advance(long n, double until);
  /// "" or the reason (naming the key) the edit was refused.
  std::string Edit(const std::string& key, const std::string& value);
  /// Restarts the run (with `seed` when given); "" or the reason it failed.
  std::string Reset(const std::optional<std::uint64_t>& seed);

 private:
  std::unique_ptr<sim::Session> session_;
};

}  // namespace formsim::python
