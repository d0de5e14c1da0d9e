// Batch runs: every job runs once, results land in their own slots, the outcome does not depend
// on the thread count, and the progress report counts every job once, in order.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include <flexstress/core/batch.hpp>

namespace test_batch {

using namespace flexstress;

// A job whose floating-point result depends on the order of its own operations only.
double job_result(std::size_t i) {
  double x = 1.0 + static_cast<double>(i);
  for (int k = 0; k < 2000; ++k) x = std::sin(x) * 1.5 + 1e-3 * static_cast<double>(k);
  return x;
}

TEST_CASE("a batch gives the serial results, whatever the thread count") {
  const std::size_t jobs = 100;
  std::vector<double> serial(jobs);
  for (std::size_t i = 0; i < jobs; ++i) serial[i] = job_result(i);
  for (unsigned threads : {1u, 2u, 3u, 7u, 0u}) {
    CAPTURE(threads);
    std::vector<double> out(jobs, 0.0);
    std::vector<int> runs(jobs, 0);
    std::vector<std::size_t> reports;
    run_batch(
        jobs, threads,
        [&](std::size_t i) {
          out[i] = job_result(i);
          ++runs[i];
        },
        [&](std::size_t done, std::size_t total) {
          CHECK(total == jobs);
          reports.push_back(done);
        });
    CHECK(out == serial);  // bit for bit
    for (int r : runs) CHECK(r == 1);
    REQUIRE(reports.size() == jobs);
    for (std::size_t k = 0; k < jobs; ++k) CHECK(reports[k] == k + 1);
  }
}

TEST_CASE("batch thread counts") {
  CHECK(batch_threads(4, 100) == 4);
  CHECK(batch_threads(8, 3) == 3);  // never more threads than jobs
  CHECK(batch_threads(2, 0) == 1);
  CHECK(batch_threads(0, 1000) >= 1);  // one per hardware thread
  int calls = 0;
  run_batch(0, 4, [&](std::size_t) { ++calls; });
  CHECK(calls == 0);
}

}  // namespace test_batch
