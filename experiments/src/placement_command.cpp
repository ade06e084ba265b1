#include "placement_command.hpp"

#include <charconv>
#include <chrono>
#include <map>
#include <string_view>
#include <variant>

#include "cli_values.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/placement_query.hpp"
#include "talus/kinematic/hait/robot.hpp"
#include "talus/report/plot.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  while (true) {
    const std::size_t comma = line.find(',');
    out.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return out;
    line.remove_prefix(comma + 1);
  }
}

double parse_field(std::string_view field, const char* name, const std::string& file,
                   std::size_t line) {
  const std::optional<std::vector<double>> v = parse_numbers(std::string(field), 1);
  if (!v) {
    fail(file, line,
         std::string(name) + " value '" + printable(std::string(field), 40) +
             "' is not a finite number");
  }
  return (*v)[0];
}

void append_number(std::string& out, double value) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, r.ptr);
}

}  // namespace

std::vector<SE2Pose> read_configurations_csv(const std::string& file) {
  std::string_view rest;
  const std::string text = read_input_file(file, kMaxPathFileBytes);
  rest = text;
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (rest.substr(0, kBom.size()) == kBom) rest.remove_prefix(kBom.size());
  std::vector<SE2Pose> out;
  std::size_t line = 0, first_blank = 0;
  bool header = false;
  while (!rest.empty()) {
    const std::size_t nl = rest.find('\n');
    const std::string_view content = trim(rest.substr(0, nl));
    rest.remove_prefix(nl == std::string_view::npos ? rest.size() : nl + 1);
    ++line;
    if (!header) {
      const auto names = split(content);
      if (names.size() != 3 || names[0] != "x" || names[1] != "y" || names[2] != "theta") {
        fail(file, line,
             "the first line must be the header 'x,y,theta', got '" +
                 printable(std::string(content), 40) + "'");
      }
      header = true;
      continue;
    }
    if (content.empty()) {
      if (!first_blank) first_blank = line;
      continue;
    }
    if (first_blank) {
      fail(file, line,
           "data after the blank line " + std::to_string(first_blank) +
               " (blank lines are allowed only at the end of the file)");
    }
    const auto f = split(content);
    if (f.size() != 3) {
      fail(file, line, "expected 3 columns x,y,theta, got " + std::to_string(f.size()));
    }
    if (out.size() == kMaxPlacementConfigurations) {
      fail(file, line,
           "more than " + std::to_string(kMaxPlacementConfigurations) +
               " configurations: their placements and output rows are held in memory; split "
               "the file");
    }
    out.push_back({parse_field(f[0], "x", file, line), parse_field(f[1], "y", file, line),
                   parse_field(f[2], "theta", file, line)});
  }
  if (!header) fail(file, 1, "empty file: expected the header line 'x,y,theta'");
  if (out.empty()) fail(file, line, "no configuration after the header");
  return out;
}

std::string placement_csv_header(const std::vector<std::string>& contact_names) {
  std::string h = "x,y,theta,z,roll,pitch";
  for (const std::string& n : contact_names) h += "," + n;
  return h + ",valid,reason";
}

nlohmann::json run_placement(const PlacementRequest& request) {
  const auto t0 = std::chrono::steady_clock::now();
  if (request.output.empty()) throw InputError("no output file given (-o OUT.csv)");
  check_output_is_not_an_input(
      "-o", request.output,
      {{"--terrain", request.terrain}, {"--robot", request.robot}, {"--configs", request.configs}});
  Robot robot = load_robot(request.robot);
  const RuledTerrain terrain(load_terrain(request.terrain, request.reproject, request.band,
                                          /*fits_surface=*/false)
                                 .grid);
  if (terrain.grid().ncols() < 2 || terrain.grid().nrows() < 2) {
    throw InputError(request.terrain + ": a placement needs at least 2 x 2 nodes");
  }
  const std::vector<SE2Pose> configs = read_configurations_csv(request.configs);
  const ElevationGrid& g = terrain.grid();
  for (std::size_t k = 0; k < configs.size(); ++k) {
    if (!terrain.contains(configs[k].position())) {
      // Blank lines only trail, so configuration k is on line k + 2.
      fail(request.configs, k + 2,
           "(" + format_number(configs[k].x) + ", " + format_number(configs[k].y) +
               ") is off the terrain " + request.terrain + ", whose domain is [" +
               format_number(g.x_min()) + ", " + format_number(g.x_max()) + "] x [" +
               format_number(g.y_min()) + ", " + format_number(g.y_max()) + "]");
    }
  }
  const bool wheeled = std::holds_alternative<WheeledRobot>(robot);
  const PlacementQuery query(terrain, std::move(robot));
  const std::vector<std::string> names = query.contact_names();
  std::string csv = placement_csv_header(names) + "\n";
  std::size_t valid = 0;
  std::map<std::string, std::size_t> reasons;
  for (const SE2Pose& q : configs) {
    const ConfigurationPlacement p = query.place(q);
    for (double v : {q.x, q.y, q.theta, p.z, p.roll, p.pitch}) {
      append_number(csv, v);
      csv += ',';
    }
    for (double v : p.contacts) {
      append_number(csv, v);
      csv += ',';
    }
    csv += p.valid ? "1," : "0,";
    csv += p.reason;
    csv += '\n';
    if (p.valid) {
      ++valid;
    } else {
      ++reasons[p.reason];
    }
  }
  write_text_file(request.output, csv);
  nlohmann::json summary;
  summary["configurations"] = configs.size();
  summary["valid"] = valid;
  summary["invalid_reasons"] = reasons;
  summary["robot_kind"] = wheeled ? "wheeled" : "articulated_chassis";
  summary["columns"] = placement_csv_header(names);
  summary["output"] = request.output;
  summary["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace talus::experiments
