// Progress of a long search on standard error: what runs, the evaluations so far, the best
// objective and the time (of the time limit, when there is one); or of a long streamed history
// (status()). On a terminal one live line is
// rewritten in place at most every 0.2 s; otherwise (a log file, a pipe, a CI job), or with
// --progress, a whole line is written every few seconds (kLogInterval, or kRequestedInterval
// with --progress, which also writes one at the first evaluation after each stage), so that a
// run that takes long is seen to be working.
#pragma once

#include "runtime/fit/fit_search.hpp"
#include "runtime/protocols/stream_history.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace rheo::cli {

inline constexpr double kLogInterval = 5.0;        // [s] between lines when standard error is not a terminal
inline constexpr double kRequestedInterval = 1.0;  // [s] between lines with --progress
inline constexpr double kQuietStart = 3.0;         // [s] before the first status() line

inline constexpr double kAnnouncedBound = 10.0;  // [s] a search's budget must allow for announce_budget()'s line

// A duration [s] in the unit a reader takes in at a glance: "40 us" below 1 ms, "0.7 ms" or
// "120 ms" below 1 s, "40 s" below 2 min, "12 min" below 2 h, "3.5 h" beyond.
std::string rough_duration(double seconds);

class Progress {
 public:
  // REQUESTED: --progress given; TIME_LIMIT: the command's bound [s], shown beside the clock.
  static std::shared_ptr<Progress> start(bool requested, std::optional<double> time_limit);

  // Names what runs next ("fitting model coupled"): written at once as a line of its own.
  void stage(const std::string& what);
  // Names what runs without a line of its own (the progress lines carry it).
  void label(const std::string& what) { what_ = what; }
  // For FitSettings::progress: called after every evaluation of a search. Its lines say what the
  // search's budget allows at the cost per evaluation so far ("the budget allows 30 s more").
  void evaluation(const runtime::SearchProgress& p);
  // After the first evaluation of each search whose budget allows more than kAnnouncedBound, a
  // line of its own at once: what an evaluation costs and how long the budget allows (`rheo fit`).
  void announce_budget() { announce_ = true; }
  // A line of its own making (a streamed history's "N samples, P % of the file"), written as
  // evaluation() writes its lines, none in the first QUIET seconds: a short run stays silent.
  // DONE in (0, 1]: the share of the work done, for the time left at the pace so far after the
  // clock ("about 4 min left"); 0: none said.
  void status(const std::string& line, double quiet = kQuietStart, double done = 0.0);
  // Clears a live line before other output.
  void finish();

  // The callbacks bound to THIS (shared: they may outlive the caller's copy).
  static std::function<void(const runtime::SearchProgress&)> evaluation_callback(const std::shared_ptr<Progress>& progress);
  static std::function<void(const std::string&)> stage_callback(const std::shared_ptr<Progress>& progress);
  // For stream_history: status() lines "N samples, P % of the file read", with the time left.
  static std::function<void(const runtime::StreamStatus&)> stream_callback(const std::shared_ptr<Progress>& progress);

 private:
  Progress(bool live, double interval, std::optional<double> time_limit);
  double elapsed() const;

  bool live_ = false;  // a terminal without --progress: one line rewritten in place
  double interval_ = kLogInterval;
  std::optional<double> time_limit_;
  std::chrono::steady_clock::time_point started_, last_;
  std::string what_;
  bool line_open_ = false;  // a live line is on the screen
  bool requested_ = false;  // --progress: also a line at the first evaluation after each stage
  bool first_of_stage_ = false;
  bool announce_ = false;
};

}  // namespace rheo::cli
