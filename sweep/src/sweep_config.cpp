#include "talus/sweep/sweep_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <sstream>

#include "talus/core/detail/strict_yaml.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

using Json = nlohmann::ordered_json;

const std::set<std::string> kTopLevelKeys = {"job",     "design",          "parameters",
                                             "cases",   "samples",         "seed",
                                             "retries", "case_time_limit", "quick"};
const std::set<std::string> kJobs = {"plan", "profile", "navigate", "noop"};

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InputError(source + ": " + what);
}

/// A YAML scalar as a JSON scalar: quoted text stays text; otherwise a
/// boolean, an integer, a number or text, whichever parses completely.
Json scalar_value(const YAML::Node& node, const std::string& source, const std::string& key) {
  if (!node.IsScalar()) fail(source, "parameter '" + key + "' must be a value or a list of values");
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;
  if (text == "true") return true;
  if (text == "false") return false;
  long long integer = 0;
  const char* end = text.data() + text.size();
  if (auto [p, ec] = std::from_chars(text.data(), end, integer); ec == std::errc() && p == end) {
    return integer;
  }
  double number = 0.0;
  if (auto [p, ec] = std::from_chars(text.data(), end, number);
      ec == std::errc() && p == end && std::isfinite(number)) {
    return number;
  }
  return text;
}

std::vector<Json> value_list(const YAML::Node& node, const std::string& source,
                             const std::string& key) {
  std::vector<Json> values;
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) values.push_back(scalar_value(item, source, key));
    if (values.empty()) fail(source, "parameter '" + key + "' has an empty list of values");
  } else {
    values.push_back(scalar_value(node, source, key));
  }
  return values;
}

std::string canonical_text(const std::string& job, const Json& parameters) {
  const nlohmann::json sorted = parameters;  // nlohmann::json sorts object keys
  return job + "\n" + sorted.dump();
}

void assign_ids(SweepConfig& config) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < config.cases.size(); ++i) {
    SweepCase& c = config.cases[i];
    c.index = i;
    c.id = fnv1a_hex(canonical_text(config.job, c.parameters));
    if (auto [it, fresh] = seen.emplace(c.id, i); !fresh) {
      fail(config.source, "cases " + std::to_string(it->second) + " and " + std::to_string(i) +
                              " have the same parameters " + c.parameters.dump());
    }
  }
  for (const SweepCase& c : config.cases) {
    for (const auto& [key, value] : c.parameters.items()) {
      if (std::find(config.keys.begin(), config.keys.end(), key) == config.keys.end()) {
        config.keys.push_back(key);
      }
    }
  }
  for (const std::string& key : config.keys) {
    const auto value_of = [&key](const SweepCase& c) {
      return c.parameters.contains(key) ? c.parameters.at(key) : Json();
    };
    const Json first = value_of(config.cases.front());
    if (std::any_of(config.cases.begin(), config.cases.end(),
                    [&](const SweepCase& c) { return value_of(c) != first; })) {
      config.swept.push_back(key);
    }
  }
}

void grid_design(SweepConfig& config, const YAML::Node& parameters) {
  std::vector<std::pair<std::string, std::vector<Json>>> axes;
  for (const auto& entry : parameters) {
    const std::string key = entry.first.as<std::string>();
    axes.emplace_back(key, value_list(entry.second, config.source, key));
  }
  // Capped like design random's samples, before any case is built (a 1e20-case grid
  // grew to gigabytes before it ran out of memory).
  double count = 1.0;
  for (const auto& axis : axes) count *= static_cast<double>(axis.second.size());
  if (count > static_cast<double>(kMaxSweepCases)) {
    std::ostringstream msg;
    msg << "design grid has " << count << " cases (the product of the parameters' list sizes); "
        << "at most " << kMaxSweepCases << ": split the sweep or use design random";
    fail(config.source, msg.str());
  }
  std::vector<Json> cases = {Json::object()};
  for (const auto& [key, values] : axes) {
    std::vector<Json> next;
    for (const Json& partial : cases) {
      for (const Json& value : values) {
        Json c = partial;
        c[key] = value;
        next.push_back(std::move(c));
      }
    }
    cases = std::move(next);
  }
  for (Json& c : cases) config.cases.push_back({0, "", std::move(c)});
}

void list_design(SweepConfig& config, const YAML::Node& parameters, const YAML::Node& cases) {
  if (!cases || !cases.IsSequence() || cases.size() == 0) {
    fail(config.source, "design list needs a non-empty `cases:` list of parameter maps");
  }
  Json common = Json::object();
  if (parameters) {
    for (const auto& entry : parameters) {
      const std::string key = entry.first.as<std::string>();
      common[key] = scalar_value(entry.second, config.source, key);
    }
  }
  for (const YAML::Node& item : cases) {
    if (!item.IsMap()) fail(config.source, "every entry of `cases:` must be a map of parameters");
    Json c = common;
    for (const auto& entry : item) {
      const std::string key = entry.first.as<std::string>();
      if (common.contains(key)) {
        fail(config.source, "parameter '" + key + "' is set both in `parameters:` and in a case");
      }
      c[key] = scalar_value(entry.second, config.source, key);
    }
    config.cases.push_back({0, "", std::move(c)});
  }
}

/// A uniform double in [0, 1) from 53 random bits: the same on every
/// standard library, unlike std::uniform_real_distribution.
double unit_draw(std::mt19937_64& random) {
  return static_cast<double>(random() >> 11) * 0x1.0p-53;
}

Json random_value(const YAML::Node& node, std::mt19937_64& random, const std::string& source,
                  const std::string& key) {
  if (node.IsMap()) {
    if (node.size() != 1 || !(node["uniform"] || node["integers"])) {
      fail(source, "parameter '" + key + "': a drawn value is {uniform: [lo, hi]} or " +
                       "{integers: [lo, hi]}");
    }
    const bool integers = static_cast<bool>(node["integers"]);
    const YAML::Node range = integers ? node["integers"] : node["uniform"];
    if (!range.IsSequence() || range.size() != 2) {
      fail(source, "parameter '" + key + "': the range must be [lo, hi]");
    }
    const Json lo = scalar_value(range[0], source, key), hi = scalar_value(range[1], source, key);
    if (!lo.is_number() || !hi.is_number() || !(lo.get<double>() <= hi.get<double>())) {
      fail(source, "parameter '" + key + "': the range must be two numbers lo <= hi");
    }
    if (integers) {
      if (!lo.is_number_integer() || !hi.is_number_integer()) {
        fail(source, "parameter '" + key + "': {integers: [lo, hi]} needs whole numbers");
      }
      const auto low = lo.get<long long>(), high = hi.get<long long>();
      const auto span = static_cast<double>(high - low + 1);
      return low + static_cast<long long>(std::floor(unit_draw(random) * span));
    }
    return lo.get<double>() + (hi.get<double>() - lo.get<double>()) * unit_draw(random);
  }
  const std::vector<Json> values = value_list(node, source, key);
  if (values.size() == 1) return values.front();
  const auto pick =
      static_cast<std::size_t>(unit_draw(random) * static_cast<double>(values.size()));
  return values[std::min(pick, values.size() - 1)];
}

void random_design(SweepConfig& config, const YAML::Node& root, const YAML::Node& parameters) {
  if (!root["samples"]) fail(config.source, "design random needs `samples:` (the number of cases)");
  const Json samples = scalar_value(root["samples"], config.source, "samples");
  if (!samples.is_number_integer() || samples.get<long long>() < 1 ||
      samples.get<long long>() > static_cast<long long>(kMaxSweepCases)) {
    fail(config.source,
         "`samples:` must be a whole number from 1 to " + std::to_string(kMaxSweepCases));
  }
  std::uint64_t seed = 0;
  if (root["seed"]) {
    const Json s = scalar_value(root["seed"], config.source, "seed");
    if (!s.is_number_unsigned() && !(s.is_number_integer() && s.get<long long>() >= 0)) {
      fail(config.source, "`seed:` must be a whole number >= 0");
    }
    seed = s.get<std::uint64_t>();
  }
  std::mt19937_64 random(seed);
  for (long long i = 0; i < samples.get<long long>(); ++i) {
    Json c = Json::object();
    for (const auto& entry : parameters) {
      const std::string key = entry.first.as<std::string>();
      c[key] = random_value(entry.second, random, config.source, key);
    }
    config.cases.push_back({0, "", std::move(c)});
  }
}

/// A parameter's value as command-line text: numbers in their shortest
/// round-trip form, text as is.
std::string value_text(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

std::string option_name(const std::string& key) {
  std::string name = key;
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

std::string absolute_text(const std::filesystem::path& base, const std::string& path) {
  const std::filesystem::path p = base.empty() || std::filesystem::path(path).is_absolute()
                                      ? std::filesystem::path(path)
                                      : base / path;
  return std::filesystem::absolute(p).lexically_normal().string();
}

}  // namespace

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char byte : text) {
    hash ^= byte;
    hash *= 1099511628211ULL;
  }
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(hash));
  return digits;
}

SweepConfig parse_sweep_config(const std::string& yaml_text, const std::string& source,
                               bool quick) {
  YAML::Node root = talus::detail::load_strict_yaml(yaml_text, source);
  SweepConfig config;
  config.source = source;
  if (!root.IsMap()) fail(source, "a sweep configuration is a map (job:, design:, parameters:)");
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    if (kTopLevelKeys.count(key) == 0) {
      fail(source, "unknown key '" + printable(key) +
                       "' (expected job, design, parameters, cases, samples, seed, retries, quick, "
                       "case_time_limit)");
    }
  }
  if (!root["job"] || !root["job"].IsScalar())
    fail(source, "missing `job:` (plan, profile, navigate, baseline NAME, noop)");
  config.job = root["job"].Scalar();
  const bool baseline = config.job.rfind("baseline ", 0) == 0 && config.job.size() > 9;
  if (kJobs.count(config.job) == 0 && !baseline) {
    fail(source, "unknown job '" + printable(config.job) +
                     "' (expected plan, profile, navigate, baseline NAME or noop)");
  }
  config.design = root["design"] ? root["design"].as<std::string>() : "grid";
  YAML::Node parameters = root["parameters"];
  if (root["quick"]) {
    if (!root["quick"].IsMap() || !parameters || !parameters.IsMap()) {
      fail(source, "`quick:` is a map of parameters (of `parameters:`) to replace in quick runs");
    }
    for (const auto& entry : root["quick"]) {
      const std::string key = entry.first.as<std::string>();
      if (!parameters[key]) fail(source, "`quick:` names '" + key + "', which is not a parameter");
      if (quick) parameters[key] = entry.second;
    }
  }
  if (parameters && !parameters.IsMap()) fail(source, "`parameters:` must be a map");
  if (root["cases"] && config.design != "list") {
    fail(source, "`cases:` belongs to design list, not design " + config.design);
  }
  if (config.design == "grid") {
    if (!parameters || parameters.size() == 0)
      fail(source, "design grid has no parameters: nothing to run");
    grid_design(config, parameters);
  } else if (config.design == "list") {
    list_design(config, parameters, root["cases"]);
  } else if (config.design == "random") {
    if (!parameters || parameters.size() == 0)
      fail(source, "design random has no parameters: nothing to run");
    random_design(config, root, parameters);
  } else {
    fail(source,
         "unknown design '" + printable(config.design) + "' (expected grid, list or random)");
  }
  if (config.design != "random" && (root["samples"] || root["seed"])) {
    fail(source, "`samples:` and `seed:` belong to design random");
  }
  if (root["retries"]) {
    const Json r = scalar_value(root["retries"], source, "retries");
    if (!r.is_number_integer() || r.get<long long>() < 0 || r.get<long long>() > 100) {
      fail(source, "`retries:` must be a whole number from 0 to 100");
    }
    config.retries = r.get<int>();
  }
  if (root["case_time_limit"]) {
    const Json t = scalar_value(root["case_time_limit"], source, "case_time_limit");
    if (!t.is_number() || !(t.get<double>() > 0.0)) {
      fail(source, "`case_time_limit:` must be a number of seconds > 0");
    }
    config.case_time_limit = t.get<double>();
  }
  assign_ids(config);
  return config;
}

SweepConfig load_sweep_config(const std::filesystem::path& path, bool quick) {
  return parse_sweep_config(read_input_file(path.string(), kMaxConfigFileBytes), path.string(),
                            quick);
}

PreparedCase prepare_case(const SweepConfig& config, const SweepCase& c,
                          const std::filesystem::path& case_dir,
                          const SweepFileCheck& check_vehicle) {
  PreparedCase prepared;
  if (config.job == "noop") {
    for (const auto& [key, value] : c.parameters.items()) {
      if (key != "sleep" && key != "crash" && key != "value") {
        throw InputError(config.source + ": job noop takes sleep, crash and value, not '" +
                         printable(key) + "'");
      }
    }
    return prepared;
  }
  std::vector<std::string> job_args;
  std::istringstream words(config.job);
  for (std::string word; words >> word;) job_args.push_back(word);

  std::vector<std::string> generate;
  std::string terrain_file, vehicle_file;
  YAML::Node vehicle_overrides(YAML::NodeType::Map);
  bool has_vehicle_override = false;
  for (const auto& [key, value] : c.parameters.items()) {
    const std::string text = value_text(value);
    if (key == "terrain.file") {
      terrain_file = absolute_text(config.base_dir, text);
    } else if (key == "terrain.generator") {
      generate.insert(generate.begin(), {"terrain", "generate", text});
    } else if (key.rfind("terrain.", 0) == 0) {
      generate.push_back(option_name(key.substr(8)));
      generate.push_back(text);
    } else if (key == "robot.file") {
      job_args.push_back("--robot");
      job_args.push_back(absolute_text(config.base_dir, text));
    } else if (key.rfind("robot.", 0) == 0) {
      throw InputError(config.source + ": parameter '" + printable(key) +
                       "': robot.file is the only robot.* key (robot files take no overrides)");
    } else if (key == "vehicle.file") {
      vehicle_file = absolute_text(config.base_dir, text);
    } else if (key.rfind("vehicle.", 0) == 0) {
      vehicle_overrides[key.substr(8)] = text;
      has_vehicle_override = true;
    } else if (key == "out" || key == "output" || key == "o") {
      throw InputError(config.source + ": parameter '" + key +
                       "' is set by the sweep (each case writes into its own folder)");
    } else if (value.is_boolean()) {
      if (value.get<bool>()) job_args.push_back(option_name(key));
    } else {
      job_args.push_back(option_name(key));
      job_args.push_back(text);
    }
  }
  const bool generated = !generate.empty();
  if (generated && generate.front() != "terrain") {
    throw InputError(config.source + ": terrain.* options need terrain.generator (a kind of " +
                     "`talus terrain generate`)");
  }
  if (generated && !terrain_file.empty()) {
    throw InputError(config.source + ": give terrain.file or terrain.generator, not both");
  }
  if (generated) {
    generate.push_back("-o");
    generate.push_back((case_dir / "terrain.asc").string());
    prepared.commands.push_back(generate);
    terrain_file = (case_dir / "terrain.asc").string();
  }
  if (!terrain_file.empty()) {
    job_args.push_back("--terrain");
    job_args.push_back(terrain_file);
  }
  if (has_vehicle_override && vehicle_file.empty()) {
    throw InputError(config.source + ": vehicle.* overrides need vehicle.file");
  }
  if (has_vehicle_override) {
    YAML::Node vehicle = talus::detail::load_strict_yaml(
        read_input_file(vehicle_file, kMaxConfigFileBytes), vehicle_file);
    for (const auto& entry : vehicle_overrides)
      vehicle[entry.first.as<std::string>()] = entry.second;
    YAML::Emitter out;
    out << vehicle;
    const std::string text = std::string(out.c_str()) + "\n";
    if (check_vehicle) check_vehicle(text, config.source + " (vehicle of case " + c.id + ")");
    prepared.files["vehicle.yaml"] = text;
    vehicle_file = (case_dir / "vehicle.yaml").string();
  }
  if (!vehicle_file.empty()) {
    job_args.push_back("--vehicle");
    job_args.push_back(vehicle_file);
  }
  job_args.push_back(config.job == "profile" ? "-o" : "--out");
  job_args.push_back((case_dir / (config.job == "profile" ? "profile.csv" : "out")).string());
  prepared.commands.push_back(job_args);
  return prepared;
}

}  // namespace talus
