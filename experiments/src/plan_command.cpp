#include "plan_command.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

#include "limits_command.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"

namespace talus::experiments {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

/// The whole of `text` as a finite double, or nothing.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const char* begin = text.data();
  if (*begin == '+') ++begin;  // from_chars refuses a leading '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(15);
  out << value;
  return out.str();
}

std::string format_point(const Vec2& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

nlohmann::json point_json(const Vec2& p) {
  return nlohmann::json::array({p.x(), p.y()});
}

/// Option checks that need no file.
void check_plan_options(const PlanRequest& request) {
  if (request.stage != kPlanStageGlobal) {
    throw InputError("--stage " + request.stage +
                     " is not available yet: only --stage global (the lattice search) is "
                     "implemented; the full pipeline comes with the local optimiser");
  }
  if (request.candidates < 1) {
    throw InputError("--candidates must be at least 1, got " + std::to_string(request.candidates));
  }
  if (!(std::isfinite(request.lattice_spacing) && request.lattice_spacing >= 0.0)) {
    throw InputError(
        "--lattice-spacing must be a finite number >= 0 [m] (0 = the terrain's "
        "cell size), got " +
        format_number(request.lattice_spacing));
  }
  if (request.connectivity != 8 && request.connectivity != 16 && request.connectivity != 32) {
    throw InputError("--connectivity must be 8, 16 or 32, got " +
                     std::to_string(request.connectivity));
  }
  if (request.smoothing && !(std::isfinite(*request.smoothing) && *request.smoothing > 0.0)) {
    throw InputError("--smoothing must be a positive finite number (lambda), got " +
                     format_number(*request.smoothing));
  }
  if (request.output_dir.empty()) throw InputError("no output folder given (--out DIR)");
  std::error_code error;
  if (std::filesystem::exists(request.output_dir, error) &&
      !std::filesystem::is_directory(request.output_dir, error)) {
    throw InputError("--out " + request.output_dir + " exists and is not a folder");
  }
}

void check_in_domain(const char* option, const Vec2& p, const ElevationGrid& grid,
                     const std::string& terrain_file) {
  if (grid.contains(p)) return;
  throw InputError(std::string(option) + " " + format_point(p) + " is off the terrain " +
                   terrain_file + ", whose domain is [" + format_number(grid.x_min()) + ", " +
                   format_number(grid.x_max()) + "] x [" + format_number(grid.y_min()) + ", " +
                   format_number(grid.y_max()) + "]");
}

std::string candidates_csv(const GlobalSearchResult& result) {
  std::string csv = kCandidatesCsvHeader;
  csv += '\n';
  for (std::size_t c = 0; c < result.candidates.size(); ++c) {
    for (const Vec2& v : result.candidates[c].vertices) {
      csv += std::to_string(c);
      csv += ',';
      append_csv_number(csv, v.x());
      csv += ',';
      append_csv_number(csv, v.y());
      csv += '\n';
    }
  }
  return csv;
}

/// One row per lattice node, row by row from the south-west; a field that was
/// not computed is `nan`.
std::string fields_csv(const GlobalSearchResult& result) {
  const std::size_t n = result.nx * result.ny;
  const auto value = [](const std::vector<double>& field, std::size_t k) {
    return field.size() == 0 ? std::numeric_limits<double>::quiet_NaN() : field[k];
  };
  std::string csv = kFieldsCsvHeader;
  csv += '\n';
  csv.reserve(csv.size() + n * 48);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 p = result.origin + result.spacing * Vec2(static_cast<double>(k % result.nx),
                                                         static_cast<double>(k / result.nx));
    for (const double v : {p.x(), p.y(), value(result.cost_from_start, k)}) {
      append_csv_number(csv, v);
      csv += ',';
    }
    append_csv_number(csv, value(result.cost_to_goal, k));
    csv += '\n';
  }
  return csv;
}

}  // namespace

Vec2 parse_point(const std::string& option, const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma != std::string::npos && text.find(',', comma + 1) == std::string::npos) {
    const std::optional<double> x = parse_number(trim(text.substr(0, comma)));
    const std::optional<double> y = parse_number(trim(text.substr(comma + 1)));
    if (x && y) return Vec2(*x, *y);
  }
  throw InputError(option + " must be X,Y: two finite numbers [m] separated by a comma, got '" +
                   text + "'");
}

PlanOutcome plan(const PlanRequest& request) {
  const auto start_time = Clock::now();
  check_plan_options(request);
  const Vec2 start = parse_point("--start", request.start);
  const Vec2 goal = parse_point("--goal", request.goal);

  const Vehicle vehicle = load_vehicle(request.vehicle);
  if (!std::isfinite(vehicle.max_speed)) {
    throw InputError(request.vehicle +
                     ": the global search needs a vehicle with a finite max_speed (its cost is "
                     "the travel time at the speed limit, and an unlimited straight road would "
                     "cost nothing); add `max_speed: V` [m/s]");
  }

  const ElevationGrid grid = read_esri_ascii(request.terrain);
  check_in_domain("--start", start, grid, request.terrain);
  check_in_domain("--goal", goal, grid, request.terrain);
  const auto fit_start = Clock::now();
  const BPatch surface = [&] {
    try {
      return request.smoothing ? BPatch::fit_smoothing(grid, *request.smoothing)
                               : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(request.terrain + ": " + e.what());
    }
  }();
  const double fit_seconds = seconds_since(fit_start);

  GlobalSearchOptions options;
  options.lattice_spacing = request.lattice_spacing;
  options.connectivity = request.connectivity;
  options.candidates = static_cast<std::size_t>(request.candidates);
  options.cost_fields = true;
  const GlobalSearchResult result = global_search(surface, vehicle, start, goal, options);
  const bool reachable = result.status == GlobalSearchStatus::kOk;

  const std::filesystem::path dir(request.output_dir);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw InputError("--out " + request.output_dir + ": cannot create the folder (" +
                     error.message() + ")");
  }
  const std::string candidates_file = (dir / "candidates.csv").string();
  const std::string fields_file = (dir / "fields.csv").string();
  const std::string summary_file = (dir / "summary.json").string();
  write_text_file(candidates_file, candidates_csv(result));
  const bool write_fields = result.nx * result.ny <= kMaxFieldNodes;
  if (write_fields) {
    write_text_file(fields_file, fields_csv(result));
  } else {
    std::filesystem::remove(fields_file, error);  // never leave a stale one
  }

  nlohmann::json candidates = nlohmann::json::array();
  for (const CandidatePath& c : result.candidates) {
    candidates.push_back({{"cost_seconds", c.cost_seconds},
                          {"length_m", c.length_m},
                          {"vertices", c.vertices.size()}});
  }
  nlohmann::json summary;
  summary["status"] = reachable ? "ok" : "unreachable";
  summary["message"] = reachable ? nlohmann::json(nullptr) : nlohmann::json(result.message);
  summary["stage"] = request.stage;
  summary["candidates"] = std::move(candidates);
  summary["candidates_requested"] = request.candidates;
  summary["start"] = point_json(start);
  summary["goal"] = point_json(goal);
  summary["start_node"] = point_json(result.start_node);
  summary["goal_node"] = point_json(result.goal_node);
  summary["lattice_spacing"] = result.spacing;
  summary["lattice"] = nlohmann::json::array({result.nx, result.ny});
  summary["connectivity"] = request.connectivity;
  summary["nodes"] = result.nodes;
  summary["edges_evaluated"] = result.edges_evaluated;
  summary["expanded"] = result.expanded;
  summary["reachable_nodes"] = result.reachable_nodes;
  summary["vehicle_max_speed"] = vehicle.max_speed;
  summary["fit"] = request.smoothing ? "smoothing" : "interpolating";
  summary["smoothing"] =
      request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(nullptr);
  summary["files"] = {{"candidates", candidates_file},
                      {"fields", write_fields ? nlohmann::json(fields_file) : nullptr},
                      {"summary", summary_file}};
  summary["fit_seconds"] = fit_seconds;
  summary["search_seconds"] = result.search_seconds;
  summary["seconds"] = seconds_since(start_time);
  write_text_file(summary_file, summary.dump(2) + "\n");
  return {std::move(summary), reachable};
}

}  // namespace talus::experiments
