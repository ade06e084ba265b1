// results.csv and report.md of a sweep (declared in sweep_runner.hpp).
#include <algorithm>
#include <map>
#include <optional>
#include <sstream>

#include "talus/report/figure.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/sweep/sweep_runner.hpp"

namespace talus {
namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

std::string csv_cell(const Json& value) {
  std::string text = value.is_null()     ? std::string()
                     : value.is_string() ? value.get<std::string>()
                                         : value.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char ch : text) {
    if (ch == '"') quoted += '"';
    quoted += ch;
  }
  return quoted + "\"";
}

/// The figure a sweep's plots show: the job's travel time when it has one,
/// else its first numeric figure.
std::string plotted_figure(const std::vector<std::string>& keys,
                           const std::map<std::string, Json>& by_id) {
  for (const char* preferred : {"travel_time", "path_length", "length_m", "value"}) {
    if (std::find(keys.begin(), keys.end(), preferred) != keys.end()) return preferred;
  }
  for (const std::string& key : keys) {
    for (const auto& [id, record] : by_id) {
      const Json& figures = record.at("figures");
      if (figures.contains(key) && figures.at(key).is_number()) return key;
    }
  }
  return {};
}

/// travel_time (or the plotted figure) against one swept numeric parameter:
/// one point per case with a finite value.
std::optional<FigureLink> parameter_figure(const SweepConfig& config,
                                           const std::map<std::string, Json>& by_id,
                                           const std::string& parameter, const std::string& figure,
                                           const fs::path& dir, std::size_t number) {
  GnuplotFigure plot(dir, "sweep_" + std::to_string(number));
  auto data = open_output_file(plot.file(".dat"));
  data << "# " << parameter << " " << figure << "\n";
  std::size_t points = 0;
  for (const SweepCase& c : config.cases) {
    const auto it = by_id.find(c.id);
    if (it == by_id.end() || !c.parameters.contains(parameter)) continue;
    const Json& x = c.parameters.at(parameter);
    const Json& figures = it->second.at("figures");
    if (!x.is_number() || !figures.contains(figure) || !figures.at(figure).is_number()) continue;
    data << x.dump() << " " << figures.at(figure).dump() << "\n";
    ++points;
  }
  close_output_file(data, plot.file(".dat"));
  if (points == 0) return std::nullopt;
  plot.describe(figure + " against " + parameter + ", one point per case", plot.name(".dat"))
      .canvas(800, 560)
      .title(figure + " against " + parameter);
  plot << "set xlabel " << gnuplot_plain_text(parameter) << "\nset ylabel "
       << gnuplot_plain_text(figure)
       << "\nset grid\nset offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  plot.plot({gnuplot_string(plot.name(".dat")) +
             " using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' notitle"});
  plot.render();
  return FigureLink{figure + " against " + parameter, plot.name(".png")};
}

}  // namespace

std::size_t write_sweep_report(const SweepConfig& config, const fs::path& dir) {
  std::map<std::string, Json> by_id;
  for (Json& record : read_sweep_records(dir))
    by_id[record.at("case_id").get<std::string>()] = record;
  std::vector<std::string> figure_keys;
  std::map<std::string, std::size_t> status_counts;
  std::size_t recorded = 0;
  for (const SweepCase& c : config.cases) {
    const auto it = by_id.find(c.id);
    if (it == by_id.end()) continue;
    ++recorded;
    ++status_counts[it->second.value("status", "")];
    for (const auto& [key, value] : it->second.at("figures").items()) {
      if (std::find(figure_keys.begin(), figure_keys.end(), key) == figure_keys.end()) {
        figure_keys.push_back(key);
      }
    }
  }
  // The job's headline figure is a column even when no case has it.
  if ((config.job == "plan" || config.job == "profile") &&
      std::find(figure_keys.begin(), figure_keys.end(), "travel_time") == figure_keys.end()) {
    figure_keys.insert(figure_keys.begin(), "travel_time");
  }
  std::ostringstream csv;
  csv << "case_id";
  for (const std::string& key : config.keys) csv << "," << csv_cell(key);
  csv << ",status";
  for (const std::string& key : figure_keys) csv << "," << csv_cell(key);
  csv << ",seconds,attempts,reason\n";
  for (const SweepCase& c : config.cases) {
    const auto it = by_id.find(c.id);
    if (it == by_id.end()) continue;
    const Json& r = it->second;
    csv << c.id;
    for (const std::string& key : config.keys) {
      csv << "," << csv_cell(c.parameters.contains(key) ? c.parameters.at(key) : Json());
    }
    csv << "," << csv_cell(r.at("status"));
    for (const std::string& key : figure_keys) {
      csv << "," << csv_cell(r.at("figures").contains(key) ? r.at("figures").at(key) : Json());
    }
    csv << "," << csv_cell(r.at("seconds")) << "," << csv_cell(r.at("attempts")) << ","
        << csv_cell(r.at("reason")) << "\n";
  }
  write_text_file(dir / "results.csv", csv.str());

  Report report("Sweep " + config.source);
  std::ostringstream intro;
  intro << "Job `" << config.job << "`, design " << config.design << ": " << config.cases.size()
        << " cases, " << recorded << " with a result (results.csv, one row per case; "
        << "results*.jsonl, one record per finished case).";
  report.paragraph(intro.str());
  Table counts({"status", "cases"});
  for (const auto& [status, count] : status_counts) counts.row({status, std::to_string(count)});
  report.heading("Status counts").table(counts);
  std::vector<FigureLink> links;
  std::vector<std::string> unplotted;
  const std::string figure = plotted_figure(figure_keys, by_id);
  if (!figure.empty() && gnuplot_available()) {
    std::size_t number = 0;
    for (const std::string& parameter : config.swept) {
      const bool numeric =
          std::any_of(config.cases.begin(), config.cases.end(), [&](const SweepCase& c) {
            return c.parameters.contains(parameter) && c.parameters.at(parameter).is_number();
          });
      if (!numeric) continue;
      if (auto link = parameter_figure(config, by_id, parameter, figure, dir, ++number)) {
        links.push_back(*link);
      } else {
        std::error_code ignored;
        fs::remove(dir / ("sweep_" + std::to_string(number) + ".dat"), ignored);
        unplotted.push_back(parameter);
      }
    }
  }
  if (!links.empty()) report.figures("One figure per swept parameter", links);
  if (!unplotted.empty()) {
    std::string names;
    for (const std::string& p : unplotted) names += (names.empty() ? "`" : ", `") + p + "`";
    report.paragraph("No case has a numeric " +
                     (figure.empty() ? std::string("figure") : "`" + figure + "`") +
                     " to plot against " + names + ".");
  }
  std::vector<std::string> failures;
  for (const SweepCase& c : config.cases) {
    const auto it = by_id.find(c.id);
    if (it != by_id.end() && !it->second.at("reason").get<std::string>().empty()) {
      failures.push_back("`" + c.id + "` " + it->second.at("status").get<std::string>() + ": " +
                         it->second.at("reason").get<std::string>());
    }
  }
  if (!failures.empty()) {
    report.heading("Cases without a result");
    for (const std::string& line : failures) report.bullet(line);
  }
  report.write(dir);
  return recorded;
}

}  // namespace talus
