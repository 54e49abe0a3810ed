// Progress of a long command: a one-line bar on stderr, only when stderr is a terminal (so that
// scripts and tests see a clean stderr); cleared when done or on error. Used by `slam`,
// `middlebury` and `cosim` (its frames).
#pragma once

#include <cstdio>
#include <string>
#include <utility>

#include <unistd.h>

namespace stereo::cli {

class ProgressBar {
  public:
    ProgressBar(std::string label, int total)
        : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) != 0) {}
    ~ProgressBar() {
        if (enabled_) {
            std::fprintf(stderr, "\r%78s\r", "");
        }
    }
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    // `done` of the total finished; `what` names the item being worked on next (may be empty).
    void update(int done, const std::string& what = "") const {
        if (!enabled_) {
            return;
        }
        constexpr int kWidth = 30;
        const int filled = total_ > 0 ? done * kWidth / total_ : kWidth;
        std::fprintf(stderr, "\r%s [%s%s] %d/%d %-20.20s", label_.c_str(),
                     std::string(filled, '#').c_str(), std::string(kWidth - filled, ' ').c_str(),
                     done, total_, what.c_str());
        std::fflush(stderr);
    }

  private:
    std::string label_;
    int total_;
    bool enabled_;
};

}  // namespace stereo::cli
