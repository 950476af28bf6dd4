// ParallelFor: every index once, the same results on any number of threads, the lowest index's error.
#include "models/core/parallel.h"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam {
namespace {

std::vector<double> SlotResults(int threads) {
  SetThreadCount(threads);
  std::vector<double> out(1000, -1.0);
  ParallelFor(out.size(), [&](std::size_t i) {
    double s = 0.0;
    for (std::size_t k = 0; k <= i; ++k) s += std::sin(static_cast<double>(k));
    out[i] = s;
  });
  return out;
}

TEST(ParallelFor, EveryIndexOnceAndTheSameResultsOnAnyThreadCount) {
  const std::vector<double> one = SlotResults(1);
  const std::vector<double> four = SlotResults(4);
  EXPECT_EQ(one, four) << "each call writes its own slot: bitwise the same";
  std::vector<std::atomic<int>> calls(257);
  ParallelFor(calls.size(), [&](std::size_t i) { ++calls[i]; });
  for (std::size_t i = 0; i < calls.size(); ++i) EXPECT_EQ(calls[i].load(), 1) << "index " << i;
  SetThreadCount(0);
  EXPECT_GE(ThreadCount(), 1);
}

TEST(ParallelFor, RethrowsTheLowestIndexError) {
  for (int threads : {1, 4}) {
    SetThreadCount(threads);
    try {
      ParallelFor(100, [](std::size_t i) {
        if (i % 10 == 7) throw InputError("item " + std::to_string(i));
      });
      FAIL() << "the loop must rethrow";
    } catch (const InputError& e) {
      EXPECT_STREQ(e.what(), "item 7") << threads << " threads";
    }
  }
  SetThreadCount(0);
}

TEST(ParallelFor, NegativeThreadCountIsAnInputError) {
  EXPECT_THROW(SetThreadCount(-1), InputError);
}

}  // namespace
}  // namespace waam
