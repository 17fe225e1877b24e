#pragma once
// The null motion model: an object stays where it was last seen (C++SORT's baseline).
#include "tracker/box.hpp"

namespace rtmot::tracker {

class StationaryPredictor {
 public:
  explicit StationaryPredictor(const Box& box) : box_(box) {}
  Box predict(double /*dt*/) const { return box_; }
  Box peek(double /*dt*/) const { return box_; }
  void update(const Box& box) { box_ = box; }
  Box box() const { return box_; }

 private:
  Box box_;
};

}  // namespace rtmot::tracker
