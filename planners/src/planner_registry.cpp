#include "talus/planners/planner_registry.hpp"

#include "talus/navigation/iagnemma_baseline.hpp"
#include "talus/planners/talus_planner.hpp"

namespace talus {

const BaselineRegistry& planner_registry() {
  static const BaselineRegistry registry = [] {
    BaselineRegistry r;
    const BaselineRegistry& baselines = BaselineRegistry::builtin();
    for (const std::string& name : baselines.names()) r.add(baselines.entry(name));
    r.add(iagnemma_baseline_entry());
    r.add(talus_planner_entry());
    return r;
  }();
  return registry;
}

}  // namespace talus
