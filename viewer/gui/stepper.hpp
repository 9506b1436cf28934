// The stepping thread: the simulation advances on a core of its own while the window draws on
// another. The thread and the window never use the Session at the same time: the window hands
// the thread one frame's stepping (start) and takes the Session back (wait) before it reads or
// edits it again, so the hand-over, under a mutex, is the only synchronisation the Session needs.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace springlab::view {

class Stepper {
 public:
  /// Starts the thread, idle; it uses one OpenMP thread (springlab::set_thread_count(1)), so the
  /// kit's parallel force code cannot take the drawing core.
  Stepper();
  ~Stepper();
  Stepper(const Stepper&) = delete;
  Stepper& operator=(const Stepper&) = delete;

  /// Hands `work` to the thread; waits first if it is still busy with earlier work.
  void start(std::function<void()> work);
  /// Returns once the thread is idle, with what the last work threw rethrown here.
  void wait();
  /// Seconds the thread spent on the work it finished since the last call.
  double take_work_seconds();

 private:
  void loop();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> work_;  // empty when idle
  bool stopping_ = false;
  double work_seconds_ = 0.0;  // since take_work_seconds
  std::exception_ptr error_;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace springlab::view
