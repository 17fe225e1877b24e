// The stationary, particle and (x, y, aspect, height) Kalman predictors.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tracker/box_geometry.hpp"
#include "tracker/kalman_predictor.hpp"
#include "tracker/particle_predictor.hpp"
#include "tracker/stationary_predictor.hpp"

namespace rtmot::tracker {
namespace {

TEST(StationaryPredictor, PredictsTheLastBoxWhateverTheTime) {
  StationaryPredictor model(Box{1.F, 2.F, 3.F, 4.F});
  model.update(Box{5.F, 6.F, 7.F, 8.F});
  const Box prior = model.predict(3.5);
  EXPECT_FLOAT_EQ(prior.x, 5.F);
  EXPECT_FLOAT_EQ(prior.h, 8.F);
  EXPECT_FLOAT_EQ(model.box().w, 7.F);
}

struct ParticleFixture {
  explicit ParticleFixture(int count) : buffer(2 * static_cast<std::size_t>(count)), n(count) {}
  ParticleStorage storage() { return ParticleStorage{buffer.data(), buffer.data() + n, n}; }
  std::vector<Particle> buffer;
  int n;
};

// A box walking right by 4 px a frame.
Box walker(int frame) {
  return Box{100.F + 4.F * frame, 50.F, 40.F, 80.F};
}

TEST(ParticlePredictor, SameSeedAndIdGiveTheSameTrajectory) {
  ParticleFixture a(64);
  ParticleFixture b(64);
  ParticlePredictor first(walker(0), a.storage(), 7, 3);
  ParticlePredictor second(walker(0), b.storage(), 7, 3);
  for (int frame = 1; frame < 20; ++frame) {
    const Box pa = first.predict(1.0);
    const Box pb = second.predict(1.0);
    EXPECT_EQ(pa.x, pb.x);
    EXPECT_EQ(pa.w, pb.w);
    first.update(walker(frame));
    second.update(walker(frame));
    EXPECT_EQ(first.box().y, second.box().y);
  }
}

TEST(ParticlePredictor, OtherSeedOrOtherTrackGivesAnotherTrajectory) {
  ParticleFixture a(64);
  ParticleFixture b(64);
  ParticleFixture c(64);
  ParticlePredictor base(walker(0), a.storage(), 7, 3);
  ParticlePredictor other_seed(walker(0), b.storage(), 8, 3);
  ParticlePredictor other_track(walker(0), c.storage(), 7, 4);
  const Box p0 = base.predict(1.0);
  EXPECT_NE(p0.x, other_seed.predict(1.0).x);
  EXPECT_NE(p0.x, other_track.predict(1.0).x);
}

TEST(ParticlePredictor, FollowsAMovingBoxAndLearnsItsVelocity) {
  ParticleFixture storage(200);
  ParticlePredictor model(walker(0), storage.storage(), 1, 1);
  for (int frame = 1; frame <= 30; ++frame) {
    model.predict(1.0);
    model.update(walker(frame));
    EXPECT_GT(iou(model.box(), walker(frame)), 0.8F) << "frame " << frame;
  }
  // Coasting: the cloud keeps moving at about 4 px a frame.
  const Box prior = model.predict(1.0);
  EXPECT_NEAR(prior.center_x(), walker(31).center_x(), 3.F);
}

TEST(ParticlePredictor, CloudSpreadsWhileNoDetectionArrives) {
  ParticleFixture storage(200);
  ParticlePredictor model(walker(0), storage.storage(), 1, 1);
  auto spread = [&storage] {
    double mean = 0.0;
    for (int i = 0; i < storage.n; ++i) mean += storage.buffer[i].cx;
    mean /= storage.n;
    double variance = 0.0;
    for (int i = 0; i < storage.n; ++i)
      variance += (storage.buffer[i].cx - mean) * (storage.buffer[i].cx - mean);
    return variance / storage.n;
  };
  // The front buffer is whichever the last resample produced; before any update it is the first.
  const double before = spread();
  for (int i = 0; i < 10; ++i) model.predict(1.0);
  EXPECT_GT(spread(), 4.0 * before);
}

TEST(ParticlePredictor, RecoversWhenNoParticleOverlapsTheObservation) {
  ParticleFixture storage(50);
  ParticlePredictor model(walker(0), storage.storage(), 1, 1);
  const Box far{1000.F, 1000.F, 40.F, 80.F};
  model.predict(1.0);
  model.update(far);
  EXPECT_GT(iou(model.box(), far), 0.7F);
}

// --- DeepSORT's and ByteTrack's (x, y, aspect, height) Kalman filter ---------------------------

TEST(XyahKalmanPredictor, StartsAtTheBoxWithUncertaintyProportionalToItsHeight) {
  const XyahKalmanPredictor model(Box{100.F, 50.F, 40.F, 80.F});
  EXPECT_DOUBLE_EQ(model.state()(0), 120.0);
  EXPECT_DOUBLE_EQ(model.state()(2), 0.5);
  EXPECT_DOUBLE_EQ(model.state()(3), 80.0);
  // ByteTrack's initiate(): 2 x h / 20 for positions, 10 x h / 160 for their velocities.
  EXPECT_DOUBLE_EQ(model.covariance()(0, 0), 8.0 * 8.0);
  EXPECT_DOUBLE_EQ(model.covariance()(7, 7), 5.0 * 5.0);
  EXPECT_DOUBLE_EQ(model.covariance()(2, 2), 1e-4);
}

TEST(XyahKalmanPredictor, FollowsAMovingBoxAndLearnsItsVelocity) {
  XyahKalmanPredictor model(walker(0));
  for (int frame = 1; frame <= 30; ++frame) {
    model.predict(1.0);
    model.update(walker(frame));
  }
  EXPECT_NEAR(model.state()(4), 4.0, 0.2);
  const Box ahead = model.predict(5.0);
  EXPECT_NEAR(ahead.x, walker(35).x, 2.0);
  EXPECT_NEAR(ahead.w, 40.F, 0.5F);
}

TEST(XyahKalmanPredictor, AScaledSceneGivesTheScaledPrediction) {
  // Its noise is proportional to the height, so a scene ten times larger is tracked exactly ten
  // times larger: the far and the near pedestrian are treated alike.
  const auto scaled = [](const Box& box, float k) {
    return Box{k * box.x, k * box.y, k * box.w, k * box.h};
  };
  XyahKalmanPredictor small(walker(0));
  XyahKalmanPredictor large(scaled(walker(0), 10.F));
  for (int frame = 1; frame <= 6; ++frame) {
    small.predict(1.0);
    large.predict(1.0);
    const Box jittered{walker(frame).x + (frame % 2 ? 1.5F : -1.F), 50.F, 40.F + frame, 80.F};
    small.update(jittered);
    large.update(scaled(jittered, 10.F));
  }
  const Box a = small.predict(3.0);
  const Box b = large.predict(3.0);
  EXPECT_NEAR(b.x, 10.F * a.x, 1e-2F);
  EXPECT_NEAR(b.w, 10.F * a.w, 1e-2F);
  EXPECT_NEAR(b.h, 10.F * a.h, 1e-2F);
}

TEST(XyahKalmanPredictor, OneStepOfTwoFramesMovesTheMeanAsTwoSteps) {
  XyahKalmanPredictor once(walker(0));
  once.predict(1.0);
  once.update(walker(1));
  XyahKalmanPredictor twice = once;
  const Box a = once.predict(2.0);
  twice.predict(1.0);
  const Box b = twice.predict(1.0);
  EXPECT_FLOAT_EQ(a.x, b.x);
  EXPECT_FLOAT_EQ(a.h, b.h);
  EXPECT_GT(once.covariance()(0, 0), 0.0);
}

TEST(XyahKalmanPredictor, AHeightDrivenThroughZeroIsNotAFiniteBox) {
  XyahKalmanPredictor model(Box{0.F, 0.F, 10.F, 20.F});
  for (int frame = 1; frame <= 4; ++frame) {
    model.predict(1.0);
    model.update(Box{0.F, 0.F, 10.F - frame, 20.F - 4.F * frame});  // shrinking fast, to 4 px
  }
  EXPECT_FALSE(is_finite(model.predict(20.0)));
}

}  // namespace
}  // namespace rtmot::tracker
