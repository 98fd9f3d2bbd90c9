#pragma once
// How far a meshing run has got, read from another thread (a GUI's progress
// bar), and a request to stop it. The pipeline names each stage as it
// starts and counts what it has done of it (faces, blocks); the stages
// call check() between steps and stop by throwing Cancelled once cancel()
// has been called.
#include <atomic>
#include <mutex>
#include <string>

namespace mm {

// Thrown by Progress::check after Progress::cancel. Not a std::exception on
// purpose: the stages catch std::exception to turn a failure into a check's
// message or a fallback, and a request to stop must pass through them all.
struct Cancelled {};

class Progress {
 public:
  struct State {
    std::string stage;  // "" before the first stage
    int done = 0;       // steps of the stage done, of total (0: not counted)
    int total = 0;
  };

  // A stage begins, with `total` steps to count (0: not counted); throws
  // Cancelled when asked to stop.
  void start_stage(const std::string& name, int total = 0) {
    check();
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stage_ = name;
    }
    done_ = 0;
    total_ = total;
  }
  // One more step of the stage done; throws Cancelled when asked to stop.
  void step() {
    ++done_;
    check();
  }
  State state() const {
    State s;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      s.stage = stage_;
    }
    s.done = done_;
    s.total = total_;
    return s;
  }

  void cancel() { cancelled_ = true; }
  bool cancelled() const { return cancelled_; }
  void check() const {
    if (cancelled_) throw Cancelled();
  }

 private:
  mutable std::mutex mutex_;  // guards stage_
  std::string stage_;
  std::atomic<int> done_{0};
  std::atomic<int> total_{0};
  std::atomic<bool> cancelled_{false};
};

// The same for an optional Progress (nullptr: nobody is watching).
inline void start_stage(Progress* progress, const std::string& name, int total = 0) {
  if (progress) progress->start_stage(name, total);
}
inline void step(Progress* progress) {
  if (progress) progress->step();
}
inline void check(const Progress* progress) {
  if (progress) progress->check();
}

}  // namespace mm
