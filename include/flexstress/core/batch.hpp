// Batch runs on one machine: independent jobs (work cycles, operators, load cases) on a fixed
// number of threads, each job writing only its own result slot, so the results do not depend
// on the thread count or on which thread ran which job: a parallel campaign equals the serial
// one bit for bit.
//
// The intended use shares the immutable parts of a simulation (a Model, modal
// body data, influence matrices) by const reference and gives each job its own mutable parts
// (State, integrator, damage meter): flexstress keeps those apart (Model/Data split), and
// nothing in the library keeps hidden mutable state in an object that is only read (the one
// exception, FusedStress::evaluate_by_influence, uses a scratch vector: give each job its own
// copy). Jobs must not throw (the library's step path never does).
//
// Uses std::thread: link Threads::Threads (CMake) or -pthread.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace flexstress {

/// Threads a batch uses when asked for `requested` (0: one per hardware thread), never more
/// than there are jobs, at least one.
inline unsigned batch_threads(unsigned requested, std::size_t jobs) {
  unsigned n = requested != 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
  if (jobs < n) n = static_cast<unsigned>(std::max<std::size_t>(jobs, 1));
  return n;
}

/// Runs job(i) for i = 0 .. jobs - 1 on batch_threads(threads, jobs) threads, taking jobs in
/// index order as threads become free. After each finished job, progress(done, jobs) is called
/// on the calling thread (for a progress line). Returns when every job has finished.
template <class Job, class Progress>
void run_batch(std::size_t jobs, unsigned threads, Job&& job, Progress&& progress) {
  const unsigned n = batch_threads(threads, jobs);
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex mutex;
  std::condition_variable finished;
  auto work = [&] {
    for (std::size_t i = next++; i < jobs; i = next++) {
      job(i);
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ++done;
      }
      finished.notify_one();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(n);
  for (unsigned k = 0; k < n; ++k) pool.emplace_back(work);
  std::size_t reported = 0;
  while (reported < jobs) {
    std::unique_lock<std::mutex> lock(mutex);
    finished.wait(lock, [&] { return done > reported; });
    const std::size_t now = done;
    lock.unlock();
    while (reported < now) progress(++reported, jobs);
  }
  for (std::thread& t : pool) t.join();
}

/// run_batch without a progress report.
template <class Job>
void run_batch(std::size_t jobs, unsigned threads, Job&& job) {
  run_batch(jobs, threads, std::forward<Job>(job), [](std::size_t, std::size_t) {});
}

}  // namespace flexstress
