// Notebook 07 — a parameter sweep: one `talus sweep` over friction and terrain
// seeds, its results read back through the library and plotted, and a second
// run that resumes and computes nothing.
//
//   build/notebooks_cpp/07_sweeps [--quick] [--out DIR] [--data DIR]
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <sys/wait.h>

#include "notebook.hpp"
#include "talus/report/plot.hpp"
#include "talus/sweep/sweep_config.hpp"
#include "talus/sweep/sweep_runner.hpp"

using namespace talus;
using namespace talus::notebooks;
namespace fs = std::filesystem;

namespace {

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `talus ARGS` (the CLI built with the project) with its output in
/// `log`; returns its exit code.
int talus_cli(const std::string& args, const fs::path& log) {
  const std::string command =
      std::string("'") + TALUS_CLI + "' " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "07_sweeps", "07 · Parameter sweeps");
    const fs::path dir = fs::absolute(nb.dir());

    nb.section("A sweep in one file");
    nb.say(
        "A sweep is a YAML file: a job (`plan`, `profile`, `baseline NAME`), a design "
        "(grid, list or seeded random samples) and the parameters — generator options as "
        "`terrain.*`, vehicle keys as `vehicle.*`, any other key an option of the job. "
        "`talus sweep CONFIG --out DIR` runs every case in its own worker process, appends "
        "one JSON line per finished case to DIR/results.jsonl, and writes results.csv and "
        "report.md. Here: the time-optimal profile along one fixed path across seeded "
        "fractal terrains, for several friction coefficients.");
    {
      std::ofstream path(dir / "path.csv");
      path << "x,y\n3,3\n12,24\n22,9\n30,29\n";
    }
    const std::string seeds = nb.quick() ? "[1, 2]" : "[1, 2, 3, 4]";
    const std::string frictions = nb.quick() ? "[0.2, 0.5, 1.0]" : "[0.2, 0.3, 0.4, 0.5, 0.7, 1.0]";
    const std::string yaml =
        "job: profile\n"
        "design: grid\n"
        "parameters:\n"
        "  terrain.generator: fractal\n"
        "  terrain.ncols: 33\n"
        "  terrain.nrows: 33\n"
        "  terrain.cellsize: 1\n"
        "  terrain.seed: " +
        seeds +
        "\n"
        "  vehicle.file: " +
        nb.data("vehicles/rover.yaml") +
        "\n"
        "  vehicle.friction: " +
        frictions +
        "\n"
        "  path: " +
        (dir / "path.csv").string() + "\n";
    write_text_file(dir / "sweep.yaml", yaml);
    nb.say("```yaml\n" + yaml + "```");

    const fs::path out = dir / "sweep";
    fs::remove_all(out);  // a fresh run each time the notebook is rendered
    const int code = talus_cli(
        "sweep '" + (dir / "sweep.yaml").string() + "' --out '" + out.string() + "' --jobs 2",
        dir / "sweep_log.txt");
    nb.check(code == 0, "`talus sweep sweep.yaml --out sweep --jobs 2` exits 0");

    nb.section("Reading the results back");
    const SweepConfig config = load_sweep_config(dir / "sweep.yaml");
    const std::vector<nlohmann::ordered_json> records = read_sweep_records(out);
    nb.say("The design has " + std::to_string(config.cases.size()) +
           " cases (swept: " + config.swept[0] + ", " + config.swept[1] +
           "); each has a stable id, a hash of its resolved parameters, so a sweep that grows "
           "keeps its finished cases.");
    nb.check(records.size() == config.cases.size(), "one record per case (" +
                                                        std::to_string(records.size()) + " of " +
                                                        std::to_string(config.cases.size()) + ")");
    // Per terrain seed: friction -> travel time (+inf where no profile exists).
    std::map<long long, std::map<double, double>> times;
    bool answered = true;
    for (const auto& r : records) {
      const std::string status = r.at("status").get<std::string>();
      answered = answered && (status == "ok" || status == "infeasible");
      const long long seed = r.at("parameters").at("terrain.seed").get<long long>();
      const double mu = r.at("parameters").at("vehicle.friction").get<double>();
      times[seed][mu] = status == "ok" ? r.at("figures").at("travel_time").get<double>() : INFINITY;
    }
    nb.check(answered,
             "every case ended with an answer: a profile, or `infeasible` with the "
             "station and the constraint that fails (no crash, no input error)");
    bool monotone = true;
    std::map<long long, Series> by_seed;
    for (const auto& [seed, curve] : times) {
      Series& s = by_seed[seed];
      s.title = "terrain seed " + std::to_string(seed);
      s.style = "linespoints lw 2 pt 7";
      double previous = INFINITY;
      for (const auto& [mu, t] : curve) {
        if (std::isfinite(t)) s.x.push_back(mu), s.y.push_back(t);
        monotone = monotone && (t <= previous * (1 + 1e-12) || std::isinf(previous));
        monotone = monotone && !(std::isinf(t) && std::isfinite(previous));
        previous = t;
      }
    }
    std::vector<Series> series;
    for (const auto& [seed, s] : by_seed) series.push_back(s);
    nb.figure("Travel time along the path against friction, per terrain",
              nb.plot("travel_time", "Time-optimal travel time against friction", "friction μ",
                      "travel time [s]", series, "set xrange [0.15:1.05]\n"));
    nb.say(
        "More friction only widens the admissible set at every station (sliding binds "
        "later, and the friction ellipse leaves more room for s̈), so the exact optimum "
        "can only get faster, and a path that is feasible at some μ stays feasible at every "
        "larger one. At μ = 0.2, where the path crosses ground steeper than "
        "atan 0.2 ≈ 11°, no speed satisfies the friction limit: those cases end "
        "`infeasible` (missing points), with the station and the constraint in results.csv. Once "
        "friction no longer binds, the curve goes flat and the "
        "top speed, drive and brake limits take over. The sweep's own report, with a "
        "figure per swept parameter, is [sweep/report.md](sweep/report.md).");
    nb.check(monotone,
             "on every terrain the travel time never increases with friction, and "
             "no case is infeasible at a higher μ than a feasible one");
    nb.check(fs::exists(out / "results.csv") && fs::exists(out / "report.md"),
             "the sweep wrote results.csv and report.md");

    nb.section("Nothing twice");
    const std::string before = file_text(out / "results.jsonl");
    const int again = talus_cli(
        "sweep '" + (dir / "sweep.yaml").string() + "' --out '" + out.string() + "' --jobs 2",
        dir / "sweep_log_resumed.txt");
    nb.say(
        "Run again on the same folder, the sweep resumes: cases whose id is already in "
        "results.jsonl are skipped. A killed sweep resumes the same way, redoing only a "
        "torn last line and the cases that had not finished.");
    nb.check(again == 0 && file_text(out / "results.jsonl") == before,
             "the second run computes nothing: results.jsonl is unchanged, byte for byte");
    return nb.finish();
  });
}
