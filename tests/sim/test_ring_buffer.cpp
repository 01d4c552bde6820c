// RingBuffer: oldest first through operator[], and ForEachRun / AppendTo give the same elements
// in the same order as at most two contiguous runs, from any start, before and after wrapping.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "sim/core/ring_buffer.hpp"

using formsim::sim::RingBuffer;

namespace {

TEST(RingBuffer, RunsGiveTheElementsInOrderFromAnyStart) {
  RingBuffer<int> r(5);
  std::vector<int> runs_seen;
  for (int pushed = 0; pushed < 13; ++pushed) {
    for (std::size_t from = 0; from <= r.size() + 1; ++from) {
      std::vector<int> expected;
      for (std::size_t i = from; i < r.size(); ++i) expected.push_back(r[i]);
      std::vector<int> got;
      int runs = 0;
      r.ForEachRun(from, [&](const int* p, std::size_t n) {
        ++runs;
        EXPECT_GT(n, 0u);
        got.insert(got.end(), p, p + n);
      });
      EXPECT_EQ(got, expected) << pushed << " pushed, from " << from;
      EXPECT_LE(runs, 2);
      std::vector<int> appended{-1};
      r.AppendTo(appended, from);
      expected.insert(expected.begin(), -1);
      EXPECT_EQ(appended, expected);
      runs_seen.push_back(runs);
    }
    r.Push(pushed);
  }
  // Both a single run and a wrapped one (two) were exercised.
  EXPECT_NE(std::count(runs_seen.begin(), runs_seen.end(), 2), 0);
  EXPECT_NE(std::count(runs_seen.begin(), runs_seen.end(), 1), 0);
  RingBuffer<int> empty(0);
  std::vector<int> out;
  empty.AppendTo(out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
