#pragma once
// One track's motion model, held by value in the track's slot: no per-track heap object.
#include <type_traits>
#include <variant>

#include "tracker/kalman_predictor.hpp"
#include "tracker/particle_predictor.hpp"
#include "tracker/stationary_predictor.hpp"

namespace rtmot::tracker {

using Predictor = std::variant<std::monostate, KalmanPredictor, XyahKalmanPredictor,
                               StationaryPredictor, ParticlePredictor>;

inline Box advance(Predictor& predictor, double dt) {
  return std::visit(
      [dt](auto& model) -> Box {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, std::monostate>) {
          return Box{};
        } else {
          return model.predict(dt);
        }
      },
      predictor);
}

/// The box advance(predictor, dt) would return, without changing the predictor.
inline Box peek(const Predictor& predictor, double dt) {
  return std::visit(
      [dt](const auto& model) -> Box {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, std::monostate>) {
          return Box{};
        } else {
          return model.peek(dt);
        }
      },
      predictor);
}

inline void correct(Predictor& predictor, const Box& box) {
  std::visit(
      [&box](auto& model) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(model)>, std::monostate>) {
          model.update(box);
        }
      },
      predictor);
}

inline Box current_box(const Predictor& predictor) {
  return std::visit(
      [](const auto& model) -> Box {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, std::monostate>) {
          return Box{};
        } else {
          return model.box();
        }
      },
      predictor);
}

}  // namespace rtmot::tracker
