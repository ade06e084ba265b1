#include "talus/core/detail/strict_yaml.hpp"

#include <yaml-cpp/eventhandler.h>

#include <map>
#include <sstream>

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

/// Counts document starts and nothing else (no nodes are built).
class DocumentCounter : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ == 2) second_ = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
  int documents() const { return documents_; }
  const YAML::Mark& second() const { return second_; }

 private:
  int documents_ = 0;
  YAML::Mark second_;
};

}  // namespace

YAML::Node load_strict_yaml(const std::string& text, const std::string& source) {
  // Not YAML::LoadAll: yaml-cpp 0.7 loops without end, allocating, on a
  // stray ',' at the top level ("#c\n,"; yaml-cpp issue 1040, found by
  // tests/robustness/test_fuzz_readers.cpp). One document is loaded, and the
  // documents are counted with a bound instead.
  YAML::Node root;
  DocumentCounter counter;
  try {
    root = YAML::Load(text);
    std::istringstream in(text);
    YAML::Parser parser(in);
    while (counter.documents() < 2 && parser.HandleNextDocument(counter)) {
    }
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
