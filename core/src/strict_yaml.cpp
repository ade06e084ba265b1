#include "talus/core/detail/strict_yaml.hpp"

#include <yaml-cpp/eventhandler.h>

#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus::detail {
namespace {

std::string line_of(const YAML::Node& node) {
  return std::to_string(node.Mark().line + 1);
}

void reject_duplicate_keys(const YAML::Node& node, const std::string& source) {
  if (node.IsMap()) {
    std::map<std::string, YAML::Node> seen;
    for (const auto& item : node) {
      const std::string key = item.first.as<std::string>("<not a scalar>");
      if (const auto earlier = seen.find(key); earlier != seen.end()) {
        throw InputError(source + ":" + line_of(item.first) + ": key '" + printable(key) +
                         "' appears twice (first on line " + line_of(earlier->second) +
                         "); give each key once");
      }
      seen.emplace(key, item.first);
      reject_duplicate_keys(item.second, source);
    }
  } else if (node.IsSequence()) {
    for (const auto& element : node) reject_duplicate_keys(element, source);
  }
}

/// Why a file's node structure is refused, and where.
struct StructureError {
  YAML::Mark mark;
  std::string message;
};

/// Walks the parser's events (no nodes are built), counts the documents and,
/// in the first, bounds the structure before yaml-cpp builds its node graph:
/// an alias to an anchor still open is a cycle (`x: &a [1, *a]`: the graph
/// is cyclic and every traversal of it recurses without end), the nesting
/// depth is at most kMaxDepth, and the node count with every alias expanded
/// (what a reader that walks the tree visits) is at most kMaxExpandedNodes,
/// so a "billion laughs" file is refused after a few thousand events. Each
/// anchored node's expanded size is computed once, when it closes.
class StructureChecker : public YAML::EventHandler {
 public:
  static constexpr std::size_t kMaxDepth = 64;
  static constexpr std::uint64_t kMaxExpandedNodes = 100'000;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ == 2) second_ = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                const std::string&) override {
    leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (documents_ > 1) return;
    if (open_anchors_.count(anchor) != 0) {
      throw StructureError{mark,
                           "an alias refers to the node that contains it (a cycle); "
                           "Talus's files hold trees"};
    }
    const auto size = sizes_.find(anchor);
    add(mark, size == sizes_.end() ? 1 : size->second);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor);
  }
  void OnMapEnd() override { close(); }

  int documents() const { return documents_; }
  const YAML::Mark& second() const { return second_; }

 private:
  struct Open {
    YAML::Mark mark;
    YAML::anchor_t anchor;
    std::uint64_t nodes;
  };

  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (documents_ > 1) return;
    if (anchor != YAML::NullAnchor) sizes_[anchor] = 1;
    add(mark, 1);
  }
  void open(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (documents_ > 1) return;
    if (stack_.size() >= kMaxDepth) {
      throw StructureError{mark, "nested more than " + std::to_string(kMaxDepth) +
                                     " levels deep; Talus's files are shallow"};
    }
    if (anchor != YAML::NullAnchor) open_anchors_.insert(anchor);
    stack_.push_back({mark, anchor, 1});
  }
  void close() {
    if (documents_ > 1 || stack_.empty()) return;
    const Open done = stack_.back();
    stack_.pop_back();
    if (done.anchor != YAML::NullAnchor) {
      open_anchors_.erase(done.anchor);
      sizes_[done.anchor] = done.nodes;
    }
    add(done.mark, done.nodes);
  }
  /// Adds `nodes` to the enclosing collection (or the document) and checks
  /// the running total; sizes stay below 2 kMaxExpandedNodes, so no overflow.
  void add(const YAML::Mark& mark, std::uint64_t nodes) {
    total_ += nodes;
    if (total_ > kMaxExpandedNodes) {
      throw StructureError{mark, "more than " + std::to_string(kMaxExpandedNodes) +
                                     " nodes with its aliases expanded (an alias bomb?)"};
    }
    if (!stack_.empty()) stack_.back().nodes += nodes;
  }

  int documents_ = 0;
  YAML::Mark second_;
  std::vector<Open> stack_;
  std::map<YAML::anchor_t, std::uint64_t> sizes_;
  std::set<YAML::anchor_t> open_anchors_;
  std::uint64_t total_ = 0;
};

}  // namespace

YAML::Node load_strict_yaml(const std::string& text, const std::string& source) {
  // Not YAML::LoadAll: yaml-cpp 0.7 loops without end, allocating, on a
  // stray ',' at the top level ("#c\n,"; yaml-cpp issue 1040, found by
  // tests/robustness/test_fuzz_readers.cpp). One document is loaded, and the
  // documents are counted with a bound instead.
  // The structure is checked on the event stream before YAML::Load builds
  // the node graph, which a cyclic alias would make cyclic.
  YAML::Node root;
  StructureChecker counter;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    while (counter.documents() < 2 && parser.HandleNextDocument(counter)) {
    }
    root = YAML::Load(text);
  } catch (const StructureError& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) + ": " + e.message);
  } catch (const YAML::Exception& e) {
    throw InputError(source + ": not valid YAML/JSON: " + printable(e.what(), 200));
  }
  if (counter.documents() > 1) {
    throw InputError(source + ":" + std::to_string(counter.second().line + 1) +
                     ": a second YAML document (or text after the first one ends); a file holds "
                     "exactly one");
  }
  reject_duplicate_keys(root, source);
  return root;
}

}  // namespace talus::detail
