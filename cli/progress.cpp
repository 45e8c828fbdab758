#include "cli/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <iostream>
#include <string>
#include <string_view>

namespace rheo::cli {

std::shared_ptr<Progress> Progress::start(bool requested, std::optional<double> time_limit) {
  const bool terminal = ::isatty(STDERR_FILENO) != 0;
  const double interval = requested ? kRequestedInterval : terminal ? 0.2 : kLogInterval;
  auto progress = std::shared_ptr<Progress>(new Progress(terminal && !requested, interval, time_limit));
  progress->requested_ = requested;
  return progress;
}

Progress::Progress(bool live, double interval, std::optional<double> time_limit)
    : live_(live), interval_(interval), time_limit_(time_limit), started_(std::chrono::steady_clock::now()), last_(started_) {}

double Progress::elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(); }

void Progress::stage(const std::string& what) {
  finish();
  what_ = what;
  first_of_stage_ = requested_;
  std::cerr << "rheo: " << what << "\n" << std::flush;
}

void Progress::evaluation(const runtime::SearchProgress& p) {
  const std::string_view what = what_.empty() ? std::string_view("searching") : std::string_view(what_);
  const double per_evaluation = p.evaluations > 0 ? p.seconds / p.evaluations : 0.0;
  const double allowed = per_evaluation * std::max(0, p.limit - p.evaluations);  // [s] the budget's evaluations left at that cost
  if (announce_ && p.evaluations == 1 && allowed > kAnnouncedBound) {
    finish();
    std::cerr << fmt::format(
                     "rheo: {}: an evaluation takes about {}, so its budget of {} evaluations allows up to about {}; "
                     "--time-limit or --max-evaluations bound it\n",
                     what, rough_duration(per_evaluation), p.limit, rough_duration(allowed))
              << std::flush;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!first_of_stage_ && std::chrono::duration<double>(now - last_).count() < interval_) return;
  first_of_stage_ = false;
  last_ = now;
  const std::string clock = time_limit_ ? fmt::format("{:.0f} s of {:g} s", elapsed(), *time_limit_) : fmt::format("{:.0f} s", elapsed());
  std::string line = fmt::format("{}: {} evaluations, best objective {:.6g} ({}), {}", what, p.evaluations, p.best, p.stage, clock);
  if (allowed > 0.0) line += fmt::format("; the budget allows {} more", rough_duration(allowed));
  if (live_) {
    std::cerr << "\r  " << line << "   " << std::flush;
    line_open_ = true;
  } else {
    std::cerr << "rheo: " << line << "\n" << std::flush;
  }
}

std::string rough_duration(double seconds) {
  if (seconds < 1e-3) return fmt::format("{:.0f} us", seconds * 1e6);
  if (seconds < 1e-2) return fmt::format("{:.1f} ms", seconds * 1e3);
  if (seconds < 1.0) return fmt::format("{:.0f} ms", seconds * 1e3);
  if (seconds < 120.0) return fmt::format("{:.0f} s", seconds);
  if (seconds < 7200.0) return fmt::format("{:.0f} min", seconds / 60.0);
  return fmt::format("{:.1f} h", seconds / 3600.0);
}

void Progress::status(const std::string& line, double quiet, double done) {
  const auto now = std::chrono::steady_clock::now();
  const double clock = elapsed();
  if (clock < quiet || std::chrono::duration<double>(now - last_).count() < interval_) return;
  last_ = now;
  std::string text = fmt::format("{}: {}, {:.0f} s", what_.empty() ? "running" : what_, line, clock);
  if (done > 0.0 && done < 1.0) text += fmt::format(", about {} left", rough_duration(clock * (1.0 - done) / done));
  if (live_) {
    std::cerr << "\r  " << text << "   " << std::flush;
    line_open_ = true;
  } else {
    std::cerr << "rheo: " << text << "\n" << std::flush;
  }
}

void Progress::finish() {
  if (line_open_) std::cerr << "\r" << std::string(120, ' ') << "\r" << std::flush;
  line_open_ = false;
}

std::function<void(const runtime::SearchProgress&)> Progress::evaluation_callback(const std::shared_ptr<Progress>& progress) {
  return [progress](const runtime::SearchProgress& p) { progress->evaluation(p); };
}

std::function<void(const std::string&)> Progress::stage_callback(const std::shared_ptr<Progress>& progress) {
  return [progress](const std::string& what) { progress->stage(what); };
}

std::function<void(const runtime::StreamStatus&)> Progress::stream_callback(const std::shared_ptr<Progress>& progress) {
  return [progress](const runtime::StreamStatus& s) {
    const double read = s.file_bytes > 0 ? static_cast<double>(s.bytes_read) / static_cast<double>(s.file_bytes) : 0.0;
    progress->status(
        s.file_bytes > 0 ? fmt::format("{} samples, {:.0f} % of the file read", s.samples, 100.0 * read) : fmt::format("{} samples", s.samples),
        kQuietStart, read);
  };
}

}  // namespace rheo::cli
