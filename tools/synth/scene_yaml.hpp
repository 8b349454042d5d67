// Scene YAML (config/scenes/*.yaml) -> SceneSpec. Every key is declared with its
// range through nerv::ConfigSection, so an unknown or out-of-range key is a
// SceneError naming the key.
#pragma once

#include <string>

#include "scene.hpp"

namespace nerv::synth {

SceneSpec loadScene(const std::string& yaml_path);
SceneSpec parseScene(const std::string& yaml_text, const std::string& name);

// "urban" -> <scenes_dir>/urban.yaml; anything with a '/' or ending in .yaml is a path.
std::string resolveScenePath(const std::string& name_or_path, const std::string& scenes_dir);

// Changes the image size keeping the field of view: fx, fy, cx scale with the
// width, cy with the height.
void resizeImage(SceneSpec& spec, int width, int height);

}  // namespace nerv::synth
