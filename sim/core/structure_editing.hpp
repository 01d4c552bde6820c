#pragma once
/// \file The optional capability of a kind whose scenario structure (its robots and how they
/// relate) can change during a run: Session::Restructure rewrites the scenario's text with it
/// and starts a new run from the result. A kind offers it by deriving from StructureEditing (or
/// from a richer capability such as formation::FormationEditing); the session and the window
/// find it with Experiment::As<StructureEditing>().

#include <string>

namespace formsim::sim {

class StructureEditing {
 public:
  virtual ~StructureEditing() = default;
  /// The scenario `text` with every robot it keeps placed where it is now, so that a run
  /// started from the result goes on from this state (undo and redo of a structural change).
  /// Throws std::runtime_error with the reason when the text cannot be rewritten.
  virtual std::string PlacedText(const std::string& text) const = 0;
};

}  // namespace formsim::sim
