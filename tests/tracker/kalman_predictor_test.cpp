// The Kalman predictor against numbers worked out by hand from sort.py's equations
// (x' = F x, P' = F P F' + Q, K = P H' (H P H' + R)^-1, with its R, P0 and Q).
#include "tracker/kalman_predictor.hpp"

#include <gtest/gtest.h>

namespace rtmot::tracker {
namespace {

constexpr Box kStart{10.F, 20.F, 30.F, 60.F};  // cx 25, cy 50, s 1800, r 0.5

TEST(KalmanPredictor, StartsAtTheBoxWithSortsInitialCovariance) {
  const KalmanPredictor kf(kStart);
  EXPECT_DOUBLE_EQ(kf.state()(0), 25.0);
  EXPECT_DOUBLE_EQ(kf.state()(1), 50.0);
  EXPECT_DOUBLE_EQ(kf.state()(2), 1800.0);
  EXPECT_DOUBLE_EQ(kf.state()(3), 0.5);
  EXPECT_DOUBLE_EQ(kf.state().tail<3>().norm(), 0.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 0), 10.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(3, 3), 10.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(4, 4), 1e4);
  EXPECT_DOUBLE_EQ(kf.covariance()(6, 6), 1e4);
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 4), 0.0);
}

TEST(KalmanPredictor, OnePredictAddsVelocityVarianceAndProcessNoise) {
  KalmanPredictor kf(kStart);
  const Box prior = kf.predict(1.0);
  EXPECT_NEAR(prior.x, 10.F, 1e-4);
  EXPECT_NEAR(prior.w, 30.F, 1e-4);
  // P00 = 10 + 1e4 + Q00 (1); P04 = 1e4; P44 = 1e4 + 0.01; P66 = 1e4 + 1e-4; P33 = 10 + 1.
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 0), 10011.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 4), 1e4);
  EXPECT_DOUBLE_EQ(kf.covariance()(4, 0), 1e4);
  EXPECT_DOUBLE_EQ(kf.covariance()(4, 4), 10000.01);
  EXPECT_DOUBLE_EQ(kf.covariance()(6, 6), 10000.0001);
  EXPECT_DOUBLE_EQ(kf.covariance()(3, 3), 11.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(3, 4), 0.0);
}

TEST(KalmanPredictor, PredictOverTwoFramesScalesTransitionAndNoise) {
  KalmanPredictor kf(kStart);
  kf.predict(2.0);
  // P00 = 10 + 2^2 * 1e4 + 2 * 1; P04 = 2 * 1e4; P44 = 1e4 + 2 * 0.01.
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 0), 40012.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 4), 2e4);
  EXPECT_DOUBLE_EQ(kf.covariance()(4, 4), 10000.02);
}

TEST(KalmanPredictor, UpdateMovesCentreAndLearnsVelocity) {
  KalmanPredictor kf(kStart);
  kf.predict(1.0);
  kf.update(Box{12.F, 20.F, 30.F, 60.F});  // centre x 27: a residual of 2 in cx only
  // The cx/vx block decouples: S = 10011 + R00 (1), K = [10011, 1e4] / 10012.
  const double s = 10012.0;
  EXPECT_NEAR(kf.state()(0), 25.0 + 2.0 * 10011.0 / s, 1e-9);
  EXPECT_NEAR(kf.state()(4), 2.0 * 1e4 / s, 1e-9);
  EXPECT_NEAR(kf.state()(1), 50.0, 1e-9);
  EXPECT_NEAR(kf.state()(5), 0.0, 1e-9);
  EXPECT_NEAR(kf.state()(2), 1800.0, 1e-9);
  // P' = P - K H P: P00 = 10011 - 10011^2 / S; P44 = 10000.01 - 1e8 / S; P04 = 1e4 - 10011e4 / S.
  EXPECT_NEAR(kf.covariance()(0, 0), 10011.0 - 10011.0 * 10011.0 / s, 1e-9);
  EXPECT_NEAR(kf.covariance()(4, 4), 10000.01 - 1e8 / s, 1e-8);
  EXPECT_NEAR(kf.covariance()(0, 4), 1e4 - 10011.0 * 1e4 / s, 1e-9);
  // The reported box is the posterior state.
  const Box posterior = kf.box();
  EXPECT_NEAR(posterior.center_x(), 25.0 + 2.0 * 10011.0 / s, 1e-4);
  EXPECT_NEAR(posterior.w, 30.0, 1e-4);
  EXPECT_NEAR(posterior.h, 60.0, 1e-4);
  // The next prior moves on by the learnt velocity.
  const Box next = kf.predict(1.0);
  EXPECT_NEAR(next.center_x(), 25.0 + 2.0 * 10011.0 / s + 2.0 * 1e4 / s, 1e-4);
}

TEST(KalmanPredictor, AreaVelocityIsZeroedBeforeItCouldMakeTheAreaNegative) {
  KalmanPredictor kf(Box{0.F, 0.F, 60.F, 30.F});  // s 1800
  kf.predict(1.0);
  kf.update(Box{0.F, 0.F, 6.F, 3.F});  // s 18: the area velocity becomes about -1780
  ASSERT_LT(kf.state()(2) + kf.state()(6), 0.0);
  const double area_before = kf.state()(2);
  const Box prior = kf.predict(1.0);
  EXPECT_DOUBLE_EQ(kf.state()(6), 0.0);
  EXPECT_DOUBLE_EQ(kf.state()(2), area_before);
  EXPECT_TRUE(std::isfinite(prior.w));
  EXPECT_NEAR(prior.w * prior.h, area_before, 1e-3);
}

TEST(KalmanPredictor, ObservationConversionsRoundTrip) {
  const auto z = KalmanPredictor::to_observation(kStart);
  EXPECT_DOUBLE_EQ(z(2), 1800.0);
  EXPECT_DOUBLE_EQ(z(3), 0.5);
  KalmanPredictor::State x = KalmanPredictor::State::Zero();
  x.head<4>() = z;
  const Box back = KalmanPredictor::to_box(x);
  EXPECT_NEAR(back.x, kStart.x, 1e-5);
  EXPECT_NEAR(back.y, kStart.y, 1e-5);
  EXPECT_NEAR(back.w, kStart.w, 1e-5);
  EXPECT_NEAR(back.h, kStart.h, 1e-5);
}

}  // namespace
}  // namespace rtmot::tracker
