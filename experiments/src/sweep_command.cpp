#include "sweep_command.hpp"

#include <iostream>
#include <memory>
#include <sstream>

#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/sweep/mpi_session.hpp"
#include "talus/sweep/sweep_config.hpp"
#include "talus/sweep/sweep_runner.hpp"

namespace talus::experiments {

void check_sweep_vehicle(const std::string& text, const std::string& source) {
  parse_vehicle(text, source);
}

std::string sweep(const SweepRequest& request) {
  const MpiSession mpi;
  const SweepConfig config = load_sweep_config(request.config);
  SweepOptions options;
  options.output_dir = request.output_dir;
  options.jobs = request.jobs;
  options.dry_run = request.dry_run;
  options.case_time_limit = request.case_time_limit;
  options.rank = mpi.rank();
  options.ranks = mpi.size();
  options.progress = request.progress && mpi.rank() == 0;
  const std::unique_ptr<CaseDealer> dealer = mpi.case_dealer();
  options.dealer = dealer.get();
  options.run_command = request.run_command;
  options.check_command = request.check_command;
  options.check_vehicle = check_sweep_vehicle;
  bool agreed = false;
  options.all_ranks_agree = [&mpi, &agreed](bool mine) {
    agreed = true;
    return mpi.all(mine);
  };
  SweepResult result;
  try {
    result = run_sweep(config, options);
  } catch (const std::exception& e) {
    // Before the ranks agreed, every rank fails alike (same config); after,
    // the others would wait for this one at the barrier for ever.
    if (agreed && mpi.size() > 1) {
      std::cerr << "talus: error: rank " << mpi.rank() << ": " << e.what() << "\n";
      mpi.abort(1);
    }
    throw;
  }
  std::ostringstream out;
  if (result.status == SweepStatus::kDryRun) {
    for (const std::string& line : result.dry_run_lines) out << line << "\n";
    out << result.mine << " cases";
    return out.str();
  }
  mpi.barrier();
  if (mpi.rank() == 0) {
    const std::size_t recorded = write_sweep_report(config, request.output_dir);
    out << result.brief_report() << "\nresults for " << recorded << " of " << config.cases.size()
        << " cases in " << request.output_dir << "/results.csv";
  }
  return out.str();
}

}  // namespace talus::experiments
