// A numerical fault inside the estimator is reported and never leaves NaN in the state.
#include <gtest/gtest.h>

#include "control/velocity/sliding_window_estimator.hpp"

namespace cv = formsim::control::velocity;

TEST(SlidingWindowEstimator, NotInitialisedIsReported) {
  cv::SlidingWindowEstimator est;
  const cv::UpdateReport r = est.AddKeyframe(1.0, {});
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.message.empty());
}

TEST(SlidingWindowEstimator, OverflowingMeasurementsGiveAFaultNotNaN) {
  cv::SlidingWindowEstimator est;
  cv::KeyframeState s;
  est.Initialize(s, {{1, 0.2}, {2, -0.3}});
  // Absurd accelerations make the residuals overflow to infinity.
  for (int k = 0; k < 50; ++k) est.AddImu(0.005, 0.0, cv::Vec2d(1e300, -1e300));
  for (int k = 0; k < 12; ++k) est.AddOdometry(0.02, 0.3, 0.0);
  const cv::UpdateReport r = est.AddKeyframe(0.25, {{1, 0.21}, {2, -0.31}});
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.message.empty());
  ASSERT_TRUE(est.initialized());
  EXPECT_TRUE(est.latest().x.allFinite());
  // The restarted window keeps working with sane data.
  for (int k = 0; k < 50; ++k) est.AddImu(0.005, 0.0, cv::Vec2d::Zero());
  for (int k = 0; k < 12; ++k) est.AddOdometry(0.02, 0.0, 0.0);
  const cv::UpdateReport r2 = est.AddKeyframe(0.5, {{1, 0.21}, {2, -0.31}});
  EXPECT_TRUE(r2.ok) << r2.message;
  EXPECT_TRUE(est.latest().x.allFinite());
}
