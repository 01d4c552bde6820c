#include "sim/core/yaml_limits.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <unordered_map>
#include <vector>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {
namespace {

// Thrown out of the event handler to stop the parse at the first problem.
struct Refusal {
  YAML::Mark mark;
  std::string why;
};

// Counts nodes as the document would expand: a scalar or a collection counts 1, an alias the
// expanded size of its anchor's subtree. Each anchor's size and height are known when its node
// ends, so the count costs one pass over the events whatever the aliases repeat.
class ExpansionCounter : public YAML::EventHandler {
 public:
  ExpansionCounter(std::size_t max_nodes, int max_depth)
      : max_nodes_(max_nodes), max_depth_(max_depth) {}

  std::size_t total() const { return total_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnAnchor(const YAML::Mark&, const std::string& name) override { pending_name_ = name; }
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { Leaf(mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                const std::string&) override {
    Leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto it = anchors_.find(anchor);
    const std::string name =
        "'*" + (it == anchors_.end() ? std::string("?") : it->second.name) + "'";
    if (it == anchors_.end() || !it->second.done)
      throw Refusal{mark, "alias " + name +
                              " refers to a node that contains it (a cycle, which no scenario "
                              "needs)"};
    const Size& s = it->second;
    if (static_cast<long long>(open_.size()) + s.height + 1 > max_depth_)
      throw Refusal{mark, "alias " + name + " nests the document deeper than " +
                              std::to_string(max_depth_) + " levels once expanded"};
    Add(mark, s.nodes, "alias " + name);
    if (!open_.empty()) open_.back().height = std::max(open_.back().height, s.height + 1);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    Open(mark, anchor);
  }
  void OnSequenceEnd() override { Close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    Open(mark, anchor);
  }
  void OnMapEnd() override { Close(); }

 private:
  struct Size {
    std::string name;
    bool done = false;
    std::size_t nodes = 0;
    long long height = 0;  // 0 for a scalar, 1 for a collection of scalars, ...
  };
  struct Frame {
    YAML::anchor_t anchor;
    std::size_t total_before;
    long long height;
  };

  void Name(YAML::anchor_t anchor) {
    if (anchor == 0) return;
    Size& s = anchors_[anchor];
    s = Size{};
    s.name = pending_name_;
    pending_name_.clear();
  }
  void Add(const YAML::Mark& mark, std::size_t n, const std::string& what) {
    if (n > max_nodes_ - std::min(max_nodes_, total_))
      throw Refusal{mark, what + " makes the document expand to more than " +
                              std::to_string(max_nodes_) +
                              " nodes (an alias counts as a copy of what it names)"};
    total_ += n;
  }
  void Leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    Name(anchor);
    Add(mark, 1, "this value");
    if (anchor != 0) {
      Size& s = anchors_[anchor];
      s.done = true;
      s.nodes = 1;
      s.height = 0;
    }
  }
  void Open(const YAML::Mark& mark, YAML::anchor_t anchor) {
    Name(anchor);
    if (static_cast<int>(open_.size()) + 1 > max_depth_)
      throw Refusal{mark, "nested deeper than " + std::to_string(max_depth_) + " levels"};
    open_.push_back({anchor, total_, 1});
    Add(mark, 1, "this collection");
  }
  void Close() {
    if (open_.empty()) return;
    const Frame f = open_.back();
    open_.pop_back();
    if (f.anchor != 0) {
      Size& s = anchors_[f.anchor];
      s.done = true;
      s.nodes = total_ - f.total_before;
      s.height = f.height;
    }
    if (!open_.empty()) open_.back().height = std::max(open_.back().height, f.height + 1);
  }

  std::size_t max_nodes_;
  int max_depth_;
  std::size_t total_ = 0;
  std::string pending_name_;
  std::vector<Frame> open_;
  std::unordered_map<YAML::anchor_t, Size> anchors_;
};

}  // namespace

void CheckYamlLimits(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  ExpansionCounter counter(kMaxYamlNodes, kMaxYamlDepth);
  try {
    parser.HandleNextDocument(counter);
  } catch (const Refusal& r) {
    throw ScenarioError(file, r.mark.line + 1, r.mark.column + 1, "", r.why);
  }
}

std::size_t ExpandedYamlNodes(const std::string& text, std::size_t stop_after) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  ExpansionCounter counter(stop_after, 1 << 30);
  try {
    parser.HandleNextDocument(counter);
  } catch (const Refusal&) {
    return stop_after + 1;
  }
  return counter.total();
}

}  // namespace formsim::sim
