// The fits `rheo fit` runs: one per fit block (or one default fit when the file has none),
// each with its model, free set, data read from disk, settings (block, then command line) and
// output path, plus running them with a progress line and Ctrl-C handling.
#pragma once

#include "lang/model.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/fit_report.hpp"

#include <csignal>

#include <atomic>
#include <string>
#include <vector>

namespace rheo::cli {

// Exit code of a fit stopped by Ctrl-C (128 + SIGINT); its best result is still written.
inline constexpr int exit_code_interrupted = 130;

struct FitOptions {
  std::string file;
  std::vector<std::string> data;
  std::string output;
  bool json = false;
  std::string model;
  int block = 0;  // 1-based index of the only fit block to run; 0: all
  std::string method;
  std::string optimizer;
  int max_evaluations = 0;  // 0: the block's or the default
  int starts = 0;
  long long seed = -1;  // -1: the block's or the default
  std::string yeoh_start;
  std::string orders;
  int threads = 1;         // data points evaluated at once; 0: every hardware thread
  std::string time_limit;  // --time-limit as written ("60s", "2 min"); empty: the block's or none
  bool progress = false;   // --progress: progress lines every second, also on a terminal (cli/progress.hpp)
};

struct FitJob {
  const lang::CheckedModel* model = nullptr;
  std::vector<int> free;
  std::vector<runtime::FitDataSet> data;
  std::vector<lang::FitData> lines;  // the fit block's data lines read into `data`; empty for --data
  int lines_block = -1;              // the index in the program's fits of the block `lines` come from; -1 for --data
  runtime::FitSettings settings;
  runtime::FitDescription description;
  std::string output;                  // fitted .rheo destination; empty: none
  std::vector<double> start_values;    // all parameters, internal units; empty: the model's
  bool steps_per_cycle_given = false;  // the fit block sets steps_per_cycle
  std::string notes;                   // said before the fit (e.g. where --yeoh-start put the yeoh spring)
  bool progress_lines = false;         // FitOptions::progress
};

std::vector<FitJob> fit_jobs(const lang::Program& program, const FitOptions& options);

// Runs the fit with progress on standard error (cli/progress.hpp); Ctrl-C stops the search with
// the best result so far (FitResult::interrupted).
runtime::FitResult run_fit_job(const FitJob& job);

// Installs the Ctrl-C handler for its lifetime (a second Ctrl-C kills as usual); flag() becomes
// true on Ctrl-C, for FitSettings::interrupt.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
  const std::atomic<bool>* flag() const;

 private:
  struct sigaction previous_ {};
};

// A duration written on the command line ("60", "60s", "2 min", "500 ms") in seconds, or the
// UsageError naming OPTION.
double duration_option(const std::string& text, const char* option);

// --orders: fits the job's model with every combination of element counts and prints a table.
int run_order_study(const std::vector<FitJob>& jobs, const FitOptions& options);

}  // namespace rheo::cli
