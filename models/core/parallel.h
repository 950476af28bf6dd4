// One thread pool for every module (oneTBB, as PrusaSlicer and OpenVDB use): how many threads the parallel loops may
// use, and a loop whose results do not depend on that number.
#pragma once

#include <cstddef>
#include <functional>

namespace waam {

// Sets the number of threads every later parallel loop may use (0 = all hardware threads, the default). Call it
// once, before the work starts (the CLI's --threads). Throws InputError for a negative count.
void SetThreadCount(int threads);
// The number of threads parallel loops may use now (>= 1).
int ThreadCount();

// Calls body(i) for every i in [0, n), on up to ThreadCount() threads, in any order. Each call must write only its
// own slot of outputs sized before the loop, so the results are the same on any number of threads. If calls throw,
// the exception of the lowest index is rethrown when the loop ends, so the error a user sees does not depend on the
// thread count either (whether calls after a throwing one ran does).
void ParallelFor(std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace waam
