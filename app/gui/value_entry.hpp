#pragma once
/// \file Typing a value into a tunable's field, the way a desktop app does it: a double-click or
/// Ctrl+click on a slider (or the palette's Enter) opens a text field over it; Enter commits,
/// Esc (or clicking elsewhere) cancels, and nothing is applied while typing. A value the loader
/// refuses keeps the field open, red, with the loader's reason; nothing is applied. The mouse
/// wheel over a slider makes a fine adjustment (FineStep). The text is in the unit shown (degrees
/// when the window shows angles in degrees); what is committed is converted back to the stored
/// unit, so the recorded edit and the saved file keep SI units and radians.

#include <string>

#include "app/render/display_unit.hpp"
#include "sim/core/param_table.hpp"

namespace formsim::app {

class ValueEntry {
 public:
  /// What the open field did in a frame.
  enum class Outcome { kNone, kCommit, kCancel };

  /// Opens the field of tunable `key`, holding `text` (the value as shown), on the next frame.
  void Open(const std::string& key, const std::string& text);
  /// The field of `key` is open.
  bool IsOpen(const std::string& key) const { return !key_.empty() && key_ == key; }
  /// The tunable whose field is open ("" none).
  const std::string& key() const { return key_; }
  /// The field is open and was drawn in this frame (keys belong to it, even before ImGui hands
  /// it the keyboard).
  bool DrawnThisFrame() const;
  /// Draws the open field (the current ImGui item width): kCommit when Enter was pressed (the
  /// text typed is text()), kCancel when Esc was pressed or the field let go, else kNone.
  Outcome Draw();
  /// The text in the field.
  std::string text() const { return buf_; }
  /// The text to commit, in the stored unit: a number typed in the unit shown (`scale`: shown =
  /// stored * scale) converted back; anything else as typed (the loader then says why not).
  std::string StoredText(double scale) const;
  /// The committed value was refused (`why`, the loader's reason): the field stays open and red.
  void Refused(const std::string& why);
  /// The text is still the one the field opened with (Enter then changes nothing).
  bool Unchanged() const { return opened_ == buf_; }
  /// Why the last commit was refused ("" none).
  const std::string& refusal() const { return refusal_; }
  void Close();

 private:
  std::string key_;
  std::string opened_;  ///< the text the field opened with
  char buf_[128] = "";
  bool focus_ = false;    ///< give the field the keyboard on its next frame
  int drawn_frame_ = -1;  ///< ImGui's frame count when last drawn
  std::string refusal_;
};

/// The text the value entry of `p` opens with: `shown` (the stored value's text), or in degrees
/// (six significant digits) when `p` is an angle shown in degrees.
std::string ParamEntryText(const sim::Param& p, const std::string& shown, bool degrees);

/// The value `steps` notches of the mouse wheel make of `value` (stored unit) for `p`: a fine
/// adjustment of one step per notch, a round power of ten of the unit shown (`scale`: shown =
/// stored * scale) at most a hundredth of the slider range (of the value, on a logarithmic
/// slider), snapped to that step and kept within the slider range. Integers move by one.
/// Returns the new value's text in the stored unit.
std::string FineStep(const sim::Param& p, double value, int steps, double scale);

}  // namespace formsim::app
