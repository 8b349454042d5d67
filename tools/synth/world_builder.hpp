// SceneSpec -> World: places the configured obstacles, then populates the road
// with random traffic and background (the scenario presets' content),
// deterministically from the scene seed.
#pragma once

#include "scene.hpp"
#include "world.hpp"

namespace nerv::synth {

// Scenery is populated over the first `route_s` seconds of driving (plus the
// view distance ahead), whatever the number of frames rendered, so that a frame
// looks the same however long the sequence is.
constexpr double kRouteSeconds = 60.0;

World buildWorld(const SceneSpec& spec);

}  // namespace nerv::synth
