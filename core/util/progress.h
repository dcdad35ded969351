// One progress reporter for every long-running CLI: a redrawn bar with rate and ETA on a terminal,
// and a plain line every few seconds otherwise (logs, CI), so output stays readable in both.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace lc2wf {

class Progress {
 public:
  Progress(std::string label, int64_t total, FILE* out = stderr)
      : label_(std::move(label)), total_(total), out_(out), tty_(isatty(fileno(out)) != 0),
        start_(Clock::now()), last_print_(start_) {}
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Advances by `n` items; `note` (e.g. "loss 0.31") is shown after the counts.
  void step(int64_t n = 1, const std::string& note = "") {
    done_ += n;
    note_ = note;
    if (done_ >= total_) return finish();
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_print_).count();
    if ((tty_ && since >= 0.1) || (!tty_ && since >= 5.0)) {
      last_print_ = now;
      print(false);
    }
  }
  void finish() {
    if (finished_) return;
    finished_ = true;
    print(true);
  }
  double elapsed_seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;

  void print(bool final_line) {
    const double elapsed = elapsed_seconds();
    const double rate = elapsed > 0 ? done_ / elapsed : 0.0;
    const double eta = (rate > 0 && total_ > done_) ? (total_ - done_) / rate : 0.0;
    const double frac = total_ > 0 ? static_cast<double>(done_) / total_ : 1.0;
    char counts[160];
    std::snprintf(counts, sizeof counts, "%lld/%lld %.1f/s %s %s", static_cast<long long>(done_),
                  static_cast<long long>(total_), rate, final_line ? "took" : "eta",
                  format_seconds(final_line ? elapsed : eta).c_str());
    if (tty_) {
      constexpr int kWidth = 28;
      const int filled = static_cast<int>(frac * kWidth + 0.5);
      std::string bar(filled, '#');
      bar.resize(kWidth, '.');
      std::fprintf(out_, "\r\033[K%s [%s] %3d%% %s %s", label_.c_str(), bar.c_str(), static_cast<int>(frac * 100),
                   counts, note_.c_str());
      if (final_line) std::fputc('\n', out_);
    } else {
      std::fprintf(out_, "%s %3d%% %s %s\n", label_.c_str(), static_cast<int>(frac * 100), counts, note_.c_str());
    }
    std::fflush(out_);
  }
  static std::string format_seconds(double s) {
    char buf[32];
    const long t = static_cast<long>(s + 0.5);
    if (t >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t % 3600) / 60);
    else std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
    return buf;
  }

  std::string label_;
  int64_t total_;
  FILE* out_;
  bool tty_;
  Clock::time_point start_, last_print_;
  int64_t done_ = 0;
  std::string note_;
  bool finished_ = false;
};

}  // namespace lc2wf
