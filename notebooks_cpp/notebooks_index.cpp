// The index page of the notebooks: DIR/index.md, one line per notebook with a
// link to its page and the count of checks its last run held. Run it after
// the notebooks; it fails if a page is missing or a run had a failed check.
//
//   build/notebooks_cpp/notebooks_index [--out DIR]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "talus/core/error.hpp"
#include "talus/report/plot.hpp"

namespace {

struct Page {
  const char* folder;
  const char* title;
  const char* what;
};

constexpr Page kPages[] = {
    {"01_terrain_and_bpatch", "01 · Terrain and B-patch",
     "a real DEM, the interpolating and smoothing B-patch fits, a path lifted onto the surface "
     "and its Darboux frame"},
    {"02_limits", "02 · Speed limits and acceleration bounds",
     "what bounds a vehicle's speed and acceleration at each station of a path, and which "
     "constraint binds"},
    {"03_time_optimal_profile", "03 · The time-optimal velocity profile",
     "the exact fastest way to drive a given path from rest to rest, its switching points "
     "and its convergence in the station spacing"},
    {"04_global_search", "04 · Global search",
     "minimum-time corridors on a lattice (cost J = ∫ ds / v_max) and distinct candidates"},
    {"05_plan", "05 · Local optimisation and the full plan",
     "`talus::plan`: candidates, B-spline optimisation of each, the best trajectory"},
    {"06_hait_baseline", "06 · The Haït–Siméon–Taïx baseline",
     "a kinematic planner through the baseline registry, its path driven time-optimally, "
     "against Talus's plan"},
    {"07_sweeps", "07 · Parameter sweeps",
     "a small resumable sweep with `talus sweep`, its results read back and plotted"},
    {"08_dacre_wright_baseline", "08 · The Dacre-Wright–Siméon baseline",
     "configuration-space boxes proven admissible from the elevation map, the (x, y, θ) "
     "octree and A* over its largest FREE voxels, through the baseline registry"},
    {"09_eldershaw_yim_baseline", "09 · The Eldershaw–Yim baseline",
     "a legged walker's footmap and CGspace from leg range and reach, the tree-PRM against "
     "one direct A*, and the footsteps along the route"},
};

/// The "N of M checks held" sentence of a page, or "" if it has none.
std::string checks_line(const std::filesystem::path& page) {
  std::ifstream in(page);
  std::string line, found;
  while (found.empty() && std::getline(in, line))
    if (line.find("checks held in this run") != std::string::npos) found = line;
  return found;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::filesystem::path out = "talus-out/notebooks";
    for (int k = 1; k < argc; ++k) {
      const std::string arg = argv[k];
      if (arg == "--out" && k + 1 < argc) {
        out = argv[++k];
      } else {
        throw talus::InputError("unknown argument '" + arg + "' (expected --out DIR)");
      }
    }
    std::ostringstream md;
    md << "# Talus notebooks\n\n"
       << "Narrated programs in `notebooks_cpp/`, read top to bottom: each builds with the "
          "project, calls the library, writes its page and figures here and checks the facts "
          "it prints. Render them all with `bash scripts/notebooks.sh` (add `--quick` for "
          "small grids); the sources are the other half of each page.\n\n";
    int missing = 0;
    for (const Page& p : kPages) {
      const std::filesystem::path page = out / p.folder / "report.md";
      const bool exists = std::filesystem::exists(page);
      const std::string checks = exists ? checks_line(page) : "";
      unsigned held = 0, total = 0;
      const bool counted = std::sscanf(checks.c_str(), "%u of %u", &held, &total) == 2;
      const bool all_held = counted && total > 0 && held == total;
      if (!exists || !all_held) ++missing;
      md << "- ";
      if (exists) {
        md << '[' << p.title << "](" << p.folder << "/report.md)";
      } else {
        md << p.title << " (not rendered)";
      }
      md << ": " << p.what;
      if (!checks.empty()) md << " — " << checks;
      md << " (source: `notebooks_cpp/" << p.folder << ".cpp`)\n";
      std::printf("%-26s %s\n", p.folder, exists ? checks.c_str() : "MISSING");
    }
    talus::write_text_file(out / "index.md", md.str());
    std::printf("index: %s\n", (out / "index.md").string().c_str());
    return missing == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "notebooks_index failed: %s\n", e.what());
    return 1;
  }
}
