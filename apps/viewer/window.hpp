#pragma once
// The interactive window: GLFW events, the Dear ImGui panel, and the frame loop. Controls are
// listed in docs/viewer.md and in the panel.

#include "scene.hpp"
#include "viewer.hpp"

namespace prt::viewer {

/// Opens a window on the scene and runs until it is closed (or Esc). Throws prt::Error when no
/// window can be opened.
void runWindow(Scene& scene, const Options& options, const Output& out);

}  // namespace prt::viewer
