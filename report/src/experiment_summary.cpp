#include "talus/report/experiment_summary.hpp"

#include <cmath>

#include "talus/report/plot.hpp"

namespace talus {

void ExperimentSummary::set(const std::string& key, double value, const std::string& unit) {
  set(key, value, unit, "");
}

void ExperimentSummary::set(const std::string& key, double value, const std::string& unit,
                            const std::string& reference) {
  numbers_[key] = {value, unit, reference};
}

double ExperimentSummary::number(const std::string& key) const {
  return numbers_.at(key).value;
}

nlohmann::json ExperimentSummary::to_json(const std::string& name, bool quick) const {
  nlohmann::json numbers = nlohmann::json::object(), units = nlohmann::json::object(),
                 references = nlohmann::json::object();
  for (const auto& [key, entry] : numbers_) {
    numbers[key] = std::isfinite(entry.value) ? nlohmann::json(entry.value) : nlohmann::json();
    units[key] = entry.unit;
    if (!entry.reference.empty()) references[key] = entry.reference;
  }
  return {{"experiment", name},
          {"quick", quick},
          {"numbers", numbers},
          {"units", units},
          {"references", references}};
}

void ExperimentSummary::write(const std::filesystem::path& file, const std::string& name,
                              bool quick) const {
  write_text_file(file, to_json(name, quick).dump(2) + "\n");
}

}  // namespace talus
