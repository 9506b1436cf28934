#include "gui/stepper.hpp"

#include "springlab/parallel.hpp"

#include <chrono>
#include <utility>

namespace springlab::view {

Stepper::Stepper() : thread_([this] { loop(); }) {}

Stepper::~Stepper() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !work_; });
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void Stepper::start(std::function<void()> work) {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !work_; });
    work_ = std::move(work);
  }
  changed_.notify_all();
}

void Stepper::wait() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !work_; });
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

double Stepper::take_work_seconds() {
  std::lock_guard lock(mutex_);
  return std::exchange(work_seconds_, 0.0);
}

void Stepper::loop() {
  set_thread_count(1);  // the other core draws
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return work_ || stopping_; });
    if (stopping_) return;
    // The work runs unlocked: wait() and start() block on work_ being set, not on the mutex.
    lock.unlock();
    const auto begun = std::chrono::steady_clock::now();
    std::exception_ptr error;
    try {
      work_();
    } catch (...) {
      error = std::current_exception();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begun).count();
    lock.lock();
    work_seconds_ += seconds;
    error_ = error;
    work_ = nullptr;
    changed_.notify_all();
  }
}

}  // namespace springlab::view
