#include "talus/kinematic/baseline_registry.hpp"

#include <utility>

#include "talus/core/error.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_baseline.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_baseline.hpp"
#include "talus/kinematic/hait/hait_baseline.hpp"

namespace talus {

const BaselineRegistry& BaselineRegistry::builtin() {
  static const BaselineRegistry registry = [] {
    BaselineRegistry r;
    r.add(hait_baseline_entry());
    r.add(dacre_wright_baseline_entry());
    r.add(eldershaw_yim_baseline_entry());
    return r;
  }();
  return registry;
}

void BaselineRegistry::add(BaselineEntry entry) {
  if (entry.name.empty()) throw InputError("BaselineRegistry::add: empty name");
  if (!entry.make) throw InputError("BaselineRegistry::add: '" + entry.name + "' has no factory");
  for (const BaselineEntry& e : entries_) {
    if (e.name == entry.name) {
      throw InputError("BaselineRegistry::add: '" + entry.name + "' is already registered");
    }
  }
  bool budget = false;
  for (const BaselineOptionSpec& s : entry.options) budget = budget || s.key == "budget";
  if (!budget) {
    throw InputError("BaselineRegistry::add: '" + entry.name + "' declares no 'budget' option");
  }
  entries_.push_back(std::move(entry));
}

std::vector<std::string> BaselineRegistry::names() const {
  std::vector<std::string> out;
  for (const BaselineEntry& e : entries_) out.push_back(e.name);
  return out;
}

const BaselineEntry& BaselineRegistry::entry(const std::string& name) const {
  for (const BaselineEntry& e : entries_) {
    if (e.name == name) return e;
  }
  std::string known;
  for (const BaselineEntry& e : entries_) known += (known.empty() ? "" : ", ") + e.name;
  throw InputError("no baseline '" + name + "'; registered: " + known);
}

std::unique_ptr<BaselinePlanner> BaselineRegistry::make(const std::string& name,
                                                        const BaselineOptions& options) const {
  return entry(name).make(options);
}

}  // namespace talus
